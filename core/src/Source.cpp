#include "hfx/core/Source.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace hfx {

std::string readTextFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(str("cannot open '", path, "'"));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

SourceFile loadSource(std::string_view name, std::string_view embedded,
                      const char* overrideDirEnv) {
    if (const char* dir = overrideDirEnv ? std::getenv(overrideDirEnv) : nullptr; dir && *dir) {
        const std::filesystem::path path = std::filesystem::path(dir) / name;
        if (std::filesystem::exists(path))
            return {std::string(name), readTextFile(path.string()), path.string()};
    }
    if (embedded.empty())
        throw Error(str("no source named '", name, "' is embedded in this build"));
    return {std::string(name), std::string(embedded), "embedded"};
}

namespace {

struct Expansion {
    const SourceLoader& load;
    const std::map<std::string, std::string, std::less<>>& slots;
    std::vector<SourceFile> parts;
    std::set<std::string, std::less<>> included;
    std::vector<std::string> open; // the files being expanded, outermost first

    void expand(const SourceFile& file) {
        open.push_back(file.name);
        included.insert(file.name);
        std::istringstream in(file.text);
        std::string line, piece;
        int number = file.firstLine, pieceStart = file.firstLine;
        auto flush = [&] {
            if (!piece.empty()) parts.push_back({file.name, piece, file.origin, pieceStart});
            piece.clear();
        };
        static const std::regex include(R"(^\s*#\s*include\b\s*(.*?)\s*(//.*)?$)");
        static const std::regex quoted(R"re(^"([^"]+)"$)re"), slot(R"(^<([^>]+)>$)");
        for (; std::getline(in, line); ++number) {
            std::smatch m;
            if (!std::regex_match(line, m, include)) {
                piece += line + '\n';
                continue;
            }
            flush();
            pieceStart = number + 1;
            const std::string target = m[1].str();
            const std::string where = str(file.name, ':', number);
            std::smatch t;
            std::string path;
            if (std::regex_match(target, t, quoted)) {
                path = t[1].str();
            } else if (std::regex_match(target, t, slot)) {
                const auto it = slots.find(t[1].str());
                if (it == slots.end()) throw Error(str(where, ": #include <", t[1].str(), ">: no file was given for that slot"));
                path = it->second;
            } else {
                throw Error(str(where, ": malformed #include '", target, "' (expected \"path\" or <slot>)"));
            }
            if (std::ranges::find(open, path) != open.end()) {
                std::string chain;
                for (const std::string& f : open) chain += f + " -> ";
                throw Error(str(where, ": #include cycle: ", chain, path));
            }
            if (!included.contains(path)) expand(load(path));
        }
        flush();
        open.pop_back();
    }
};

} // namespace

std::vector<SourceFile> expandIncludes(const SourceFile& top, const SourceLoader& load,
                                       const std::map<std::string, std::string, std::less<>>& slots) {
    Expansion e{load, slots, {}, {}, {}};
    e.expand(top);
    return std::move(e.parts);
}

} // namespace hfx
