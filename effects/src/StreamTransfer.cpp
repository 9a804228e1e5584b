#include "StreamTransfer.h"

#include "hfx/core/Error.h"
#include "hfx/core/GlFence.h"

#include <cstring>

namespace hfx {
namespace {

constexpr GLbitfield kMapping = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
constexpr size_t kAlignment = 256; // GL_PIXEL_UNPACK_BUFFER offsets, and the cache lines under them

size_t aligned(size_t bytes) { return (bytes + kAlignment - 1) / kAlignment * kAlignment; }

const char* streamName(int stream) {
    static const char* const kNames[] = {"texels", "pyramid", "albedo", "shading channels"};
    return kNames[stream];
}

} // namespace

StreamTransfer::StreamTransfer(ClContext& cl, TransferPath path) : cl_(cl), path_(path) {
    if (path != TransferPath::Staged && path != TransferPath::GlSharing && path != TransferPath::ExternalMemory)
        throw Error(str("StreamTransfer: the ", transferPathName(path), " path is not one of its three"));
    if (path == TransferPath::GlSharing)
        if (const std::string why = transferPathRefusal(cl, path); !why.empty()) throw Error(why);
    if (path == TransferPath::ExternalMemory) external_ = std::make_unique<ExternalMemory>(cl);
    acquired_.reserve(kStreams);
    acquiredExternal_.reserve(kStreams);
}

StreamTransfer::~StreamTransfer() {
    try {
        cl_.queue().finish(); // reads into pinned memory, copies into shared buffers
    } catch (...) {
        // Destructors never throw; a failed finish leaves nothing running to wait for.
    }
    for (GLsync& f : fences_)
        if (f) glDeleteSync(f);
    for (StreamMemory& m : streams_) {
        if (m.ringMemory && m.ring.id()) glUnmapNamedBuffer(m.ring.id());
        if (m.pinnedMemory) {
            try {
                cl_.queue().enqueueUnmapMemObject(m.pinned, m.pinnedMemory);
                cl_.queue().finish();
            } catch (...) {
            }
        }
    }
}

void StreamTransfer::allocate(StreamMemory& m, size_t bytes) {
    m.bytes = bytes;
    if (path_ == TransferPath::Staged) {
        clGuard("allocating pinned host memory for the transfer", [&] {
            m.pinned = cl::Buffer(cl_.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, bytes);
            m.pinnedMemory =
                cl_.queue().enqueueMapBuffer(m.pinned, CL_TRUE, CL_MAP_READ | CL_MAP_WRITE, 0, bytes);
        });
        std::memset(m.pinnedMemory, 0, bytes); // the pages touched once, now, not in a frame
        m.slotStride = aligned(bytes);
        m.ring = GlBuffer::create();
        HFX_GL_CHECK(glNamedBufferStorage(m.ring.id(), GLsizeiptr(2 * m.slotStride), nullptr, kMapping));
        m.ringMemory =
            static_cast<unsigned char*>(glMapNamedBufferRange(m.ring.id(), 0, GLsizeiptr(2 * m.slotStride), kMapping));
        if (!m.ringMemory)
            throw Error(str("the staged transfer could not map a ", 2 * m.slotStride,
                            "-byte pixel buffer persistently (GL error 0x", std::hex, glGetError(), ")"));
        std::memset(m.ringMemory, 0, 2 * m.slotStride);
    } else if (path_ == TransferPath::ExternalMemory) {
        for (Slot& s : m.slots) s.external = external_->allocate(bytes);
    } else {
        for (Slot& s : m.slots) {
            s.gl = GlBuffer::create();
            HFX_GL_CHECK(glNamedBufferStorage(s.gl.id(), GLsizeiptr(bytes), nullptr, 0));
            glFinish(); // the buffer exists for GL before CL takes it
            clGuard("sharing a GL buffer with OpenCL (clCreateFromGLBuffer)",
                    [&] { s.shared = cl::BufferGL(cl_.context(), CL_MEM_WRITE_ONLY, s.gl.id()); });
            s.objects = {s.shared};
        }
    }
}

void StreamTransfer::waitForGl(int slot) { waitAndDelete(fences_[size_t(slot)], "the transfer's pixel buffer"); }

void StreamTransfer::enqueue(Stream stream, const cl::Buffer& source, size_t bytes) {
    StreamMemory& m = streams_[stream];
    if (m.bytes == 0) allocate(m, bytes);
    if (bytes > m.bytes)
        throw Error(str("StreamTransfer: the ", streamName(stream), " grew from ", m.bytes, " to ", bytes, " bytes"));
    cl::CommandQueue& q = cl_.queue();
    if (path_ == TransferPath::Staged) {
        // The pinned memory is free: the last frame's arrive() copied it out before this submit.
        clGuard("reading the surface into pinned memory",
                [&] { q.enqueueReadBuffer(source, CL_FALSE, 0, bytes, m.pinnedMemory); });
    } else if (path_ == TransferPath::ExternalMemory) {
        // GL read this slot's memory two frames ago: finished before the device writes it again.
        if (acquiredExternal_.empty()) waitForGl(slot_);
        const cl::Buffer& shared = m.slots[size_t(slot_)].external.cl();
        acquiredExternal_.push_back(shared()); // capacity for every stream, reserved at construction
        external_->acquire({&acquiredExternal_.back(), 1});
        clGuard("copying the surface into the shared memory",
                [&] { q.enqueueCopyBuffer(source, shared, 0, 0, bytes); });
    } else {
        // GL read this slot's buffers two frames ago: the extension wants that finished first.
        if (acquired_.empty()) waitForGl(slot_);
        const Slot& s = m.slots[size_t(slot_)];
        clGuard("acquiring a shared GL buffer", [&] { q.enqueueAcquireGLObjects(&s.objects); });
        acquired_.push_back(s.shared); // capacity for every stream, reserved at construction
        clGuard("copying the surface into the shared GL buffer",
                [&] { q.enqueueCopyBuffer(source, m.slots[size_t(slot_)].shared, 0, 0, bytes); });
    }
    m.enqueued = true;
}

void StreamTransfer::arrive() {
    if (path_ == TransferPath::ExternalMemory) {
        external_->release(acquiredExternal_); // returns once GL may read them
        acquiredExternal_.clear();
        return;
    }
    if (path_ == TransferPath::GlSharing) {
        if (!acquired_.empty()) {
            cl::Event released;
            clGuard("releasing the shared GL buffers", [&] {
                cl_.queue().enqueueReleaseGLObjects(&acquired_, nullptr, &released);
                released.wait(); // GL may read them only once the device is done with them
            });
            acquired_.clear();
        }
        return;
    }
    waitForGl(slot_); // GL's reads of this slot, two frames ago
    for (StreamMemory& m : streams_)
        if (m.enqueued) std::memcpy(m.ringMemory + size_t(slot_) * m.slotStride, m.pinnedMemory, m.bytes);
}

const void* StreamTransfer::source(Stream stream) {
    StreamMemory& m = streams_[stream];
    HFX_CHECK(m.enqueued);
    if (path_ == TransferPath::Staged) {
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, m.ring.id());
        // With an unpack buffer bound, GL reads the pointer as an offset into it.
        return reinterpret_cast<const void*>(size_t(slot_) * m.slotStride);
    }
    const Slot& s = m.slots[size_t(slot_)];
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, path_ == TransferPath::ExternalMemory ? s.external.gl() : s.gl.id());
    return nullptr;
}

std::string StreamTransfer::description() const { return external_ ? external_->description() : ""; }

void StreamTransfer::unbind() { glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0); }

void StreamTransfer::uploaded() {
    if (fences_[size_t(slot_)]) glDeleteSync(fences_[size_t(slot_)]);
    fences_[size_t(slot_)] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    for (StreamMemory& m : streams_) m.enqueued = false;
    slot_ = 1 - slot_;
}

} // namespace hfx
