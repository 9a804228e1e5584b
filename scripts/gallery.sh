#!/usr/bin/env bash
# Renders the README's gallery: one 1280x720 picture of each scene, headless, at the scenes'
# default grazing cameras, after enough frames for the field to develop (the seas' foam with 20 s
# of wind behind it, --foam-history; the decal volley: 196 bullets and 5 explosions with their
# scorch; the planet's storms). Writes
# docs/gallery/{water,decals,planet,noise}.jpg, the wall's bricks and damage on a column
# (decals-pillar.jpg), a fresh crater on the wall close up (decals-closeup.jpg), the noise on a rounded box (noise-triplanar.jpg),
# the planet close up (planet-closeup.jpg), with rings (planet-rings.jpg) and over its pole (planet-pole.jpg), the sea
# calm (Beaufort 3) and rough (Beaufort 7), a Beaufort 4 / 7 / 10 strip, the far field seen 5 degrees down (water-horizon.jpg),
# the sea after an explosion (water-explosion.jpg), from 120 m up (water-above.jpg), and a 4-second 640x360 video of the rough sea
# (water.mp4, needs ffmpeg). `bash scripts/gallery.sh water` (or decals, noise, planet) renders one
# scene's pictures only.
set -euo pipefail
only=${1:-all}
case "$only" in all | water | decals | noise | planet) ;; *) echo "gallery.sh: unknown scene '$only' (water, decals, noise, planet)" >&2; exit 2 ;; esac
wanted() { [[ $only == all || $only == "$1" ]]; }
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p docs/gallery
render() { # scene frames [options...]
    local scene=$1 frames=$2
    shift 2
    rm -rf "${work:?}/$scene" # no frames left from an earlier render of the scene
    ./build/demo/hfx-demo "$scene" --headless --frames "$frames" --format jpg --out "$work/$scene" "$@"
    cp "$(ls "$work/$scene"/*.jpg | tail -n 1)" "docs/gallery/$scene.jpg"
}
if wanted water; then
    render water 30 --foam-history 20 --beaufort 3 && mv docs/gallery/water.jpg docs/gallery/water-calm.jpg
    render water 30 --foam-history 20 --beaufort 7 && mv docs/gallery/water.jpg docs/gallery/water-rough.jpg
    render water 30 --foam-history 20 --beaufort 4 && mv docs/gallery/water.jpg docs/gallery/water-beaufort4.jpg
    render water 30 --foam-history 20 --beaufort 10 && mv docs/gallery/water.jpg docs/gallery/water-beaufort10.jpg
    render water 30 --foam-history 20 --camera-pitch 5 && mv docs/gallery/water.jpg docs/gallery/water-horizon.jpg
    render water 30 --foam-history 20 --camera-height 120 --camera-pitch 35 && mv docs/gallery/water.jpg docs/gallery/water-above.jpg
    if command -v ffmpeg >/dev/null; then
        # Encoded here rather than by --video: a higher CRF keeps the committed file small.
        ./build/demo/hfx-demo water --headless --frames 120 --width 640 --height 360 --beaufort 7 --foam-history 20 --format jpg \
            --out "$work/video" --no-progress >/dev/null
        ffmpeg -loglevel error -y -framerate 30 -i "$work/video/water_%04d.jpg" -c:v libx264 -crf 30 -preset slow \
            -pix_fmt yuv420p -movflags +faststart docs/gallery/water.mp4
    fi
    # The ocean one second after an explosion (and two bullets) fired from the camera.
    printf 'explosion 1 760 560 3\nclick 1 420 600\nclick 1 440 610\n' > "$work/water-shots.txt"
    render water 31 --foam-history 20 --shots "$work/water-shots.txt" && mv docs/gallery/water.jpg docs/gallery/water-explosion.jpg
    render water 30 --foam-history 20
fi
if wanted decals; then
    render decals 50 --pillar && mv docs/gallery/decals.jpg docs/gallery/decals-pillar.jpg
    render decals 50 --camera-target -1.2,-0.4,0 --camera-azimuth 15 --camera-elevation 5 --camera-distance 1.3 && mv docs/gallery/decals.jpg docs/gallery/decals-closeup.jpg
    render decals 50
fi
if wanted noise; then
    render noise 2 --noise-kind psrd --fractal ridged --warp 0.6 --triplanar 0.8 && mv docs/gallery/noise.jpg docs/gallery/noise-triplanar.jpg
    render noise 2 --noise-kind psrd --fractal ridged --warp 0.6
fi
if wanted planet; then
    # The planet as a GPU draws it (4 detail texels per gas cell) after its minute of spin-up, and a close-up after 12 s more
    # of its gas (the festoons and filaments of its advected detail).
    render planet 150 --detail-scale 4 --camera-distance 1.8 --time-scale 3 && mv docs/gallery/planet.jpg docs/gallery/planet-closeup.jpg
    render planet 120 --detail-scale 4 --rings 1 --camera-distance 5 && mv docs/gallery/planet.jpg docs/gallery/planet-rings.jpg
    # Its north polar cap from 70 degrees up (its gas on the sphere: no starburst where the meridians meet).
    render planet 120 --detail-scale 4 --camera-elevation 70 --camera-distance 2.2 && mv docs/gallery/planet.jpg docs/gallery/planet-pole.jpg
    render planet 120 --detail-scale 4
fi
ls -l docs/gallery
