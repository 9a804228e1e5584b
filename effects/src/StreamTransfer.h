#pragma once
// The three transfer paths that keep a device's results in device memory until they are copied
// (SurfacePipeline's TransferPath::Staged, GlSharing and ExternalMemory), behind one interface:
//
//   enqueue(stream, buffer)   // in submit(): the copy enqueued behind the frame's kernels
//   ... the caller waits for the queue (its frame marker) ...
//   arrive()                  // in finish(): what the copies brought, ready for GL
//   upload from source(stream) with the pixel buffer bound, for each stream enqueued
//   uploaded()                // GL's reads fenced; the next frame takes the other slot
//
// Staged (a discrete GPU without sharing): per stream a pinned CL host buffer
// (CL_MEM_ALLOC_HOST_PTR, mapped once, its pages touched once) that a non-blocking read fills at
// the device's copy speed, and a persistently mapped GL pixel buffer of two slots: arrive()
// copies the pinned bytes into the free slot (waiting for GL to have read that slot two frames
// ago), GL uploads from it. The read overlaps whatever the host does between submit() and
// finish() (in the overlapped frame, the previous frame's draw).
//
// GlSharing (cl_khr_gl_sharing for the caller's GL context, ClContext::sharesGl()): per stream
// two GL buffers that the device's queue copies into between clEnqueueAcquireGLObjects and
// clEnqueueReleaseGLObjects; GL uploads from them without a host copy. The copy into a buffer
// waits (a GL fence) until GL has read it two frames ago, as the sharing extension requires.
//
// ExternalMemory (ExternalMemory.h: memory Vulkan allocates and both GL and the device import):
// per stream two such buffers, used as GlSharing's are (the device's queue copies into one between
// cl_khr_external_memory's acquire and release, GL uploads from it, a fence guards its reuse).
//
// A stream's memory is made on its first enqueue. Owns its CL and GL objects. Thread: the thread
// that owns both the ClContext and the current GL context.

#include "ExternalMemory.h"

#include "hfx/compute/ClContext.h"
#include "hfx/core/GlObject.h"
#include "hfx/effects/TransferPath.h"

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace hfx {

class StreamTransfer {
public:
    enum Stream { Texels, Pyramid, Albedo, Channels, kStreams };

    /// path: TransferPath::Staged, GlSharing (needs cl.sharesGl()) or ExternalMemory (needs
    /// ExternalMemory::unavailable(cl) to be "", else throws its reason).
    StreamTransfer(ClContext& cl, TransferPath path);
    /// Waits for the device's copies and GL's reads before the memory goes.
    ~StreamTransfer();
    StreamTransfer(const StreamTransfer&) = delete;
    StreamTransfer& operator=(const StreamTransfer&) = delete;

    /// Enqueues the copy of the first `bytes` of `source` for this frame (a stream's size is fixed
    /// by its first enqueue; a larger one later is refused by name).
    void enqueue(Stream stream, const cl::Buffer& source, size_t bytes);
    /// Call after the queue has finished the frame's work: the enqueued streams are ready to upload.
    void arrive();
    /// The source pointer of `stream` for a GL upload call, its pixel buffer bound as
    /// GL_PIXEL_UNPACK_BUFFER (unbind() after the call).
    const void* source(Stream stream);
    void unbind();
    /// After this frame's uploads: fences GL's reads of its memory and moves to the other slot.
    void uploaded();
    /// What the path's memory is, where it says more than its name (ExternalMemory's); else "".
    std::string description() const;

private:
    struct Slot {
        GlBuffer gl;            ///< GlSharing: the shared buffer of this slot
        cl::BufferGL shared;    ///< GlSharing: its CL view
        std::vector<cl::Memory> objects; ///< GlSharing: {shared}, as the acquire call takes it (made once)
        ExternalMemory::SharedBuffer external; ///< ExternalMemory: this slot's memory
    };
    struct StreamMemory {
        size_t bytes = 0;
        bool enqueued = false;  ///< copied this frame
        // Staged:
        cl::Buffer pinned;          ///< CL_MEM_ALLOC_HOST_PTR, mapped once
        void* pinnedMemory = nullptr;
        GlBuffer ring;              ///< two slots of `bytes` (256-byte aligned), persistently mapped
        unsigned char* ringMemory = nullptr;
        size_t slotStride = 0;
        // GlSharing, ExternalMemory:
        std::array<Slot, 2> slots;
    };
    void allocate(StreamMemory& m, size_t bytes);
    void waitForGl(int slot); ///< until GL has read `slot`'s memory (its fence)

    ClContext& cl_;
    TransferPath path_;
    std::unique_ptr<ExternalMemory> external_; ///< ExternalMemory: the allocator (outlives the streams' memory)
    std::array<StreamMemory, kStreams> streams_;
    std::array<GLsync, 2> fences_{nullptr, nullptr};
    int slot_ = 0;
    std::vector<cl::Memory> acquired_; ///< GlSharing: this frame's buffers the queue holds
    std::vector<cl_mem> acquiredExternal_; ///< ExternalMemory: the same
};

} // namespace hfx
