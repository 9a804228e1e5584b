#pragma once
// Memory that the compute device and GL both address, for TransferPath::ExternalMemory (the
// StreamTransfer's third path). Neither OpenCL nor GL exports its own memory, so Vulkan allocates
// it (VK_KHR_external_memory_fd) on the physical device that GL draws with (the device UUID of
// GL_EXT_memory_object), and both import it by file descriptor:
// - GL as a buffer (GL_EXT_memory_object_fd), which uploads to textures as a pixel buffer;
// - OpenCL as a buffer by the same descriptor (cl_khr_external_memory_opaque_fd, a GPU's driver:
//   NVIDIA's, whose OpenCL shares no memory with an EGL context otherwise), on the device whose
//   UUID is the memory's (cl_khr_device_uuid); or, where the compute device shares host memory (a
//   CPU device) and the memory is host-visible, over Vulkan's mapping of it (CL_MEM_USE_HOST_PTR).
// The device copies a frame's results into it and GL uploads from it: no host copy, no bus.
//
// Vulkan is loaded at run time (libvulkan.so.1, its loader): HFX neither links nor needs it, and
// `unavailable` says what a machine lacks (the loader, a Vulkan device that is GL's, an extension
// of any of the three).
//
// The process keeps one Vulkan instance from its first use to its end (a loader unloads its
// drivers with their last instance; made for every question, they leaked a little each time in
// lavapipe, and cost as much again). Owns its Vulkan device, and each SharedBuffer its allocation
// and imports (made and destroyed with the GL context current; destroyed before their
// ExternalMemory). Thread: the
// thread that owns the ClContext, with the GL context current.

#include "hfx/compute/ClContext.h"
#include "hfx/core/GlObject.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace hfx {

class ExternalMemory {
public:
    /// How the compute device takes the memory.
    enum class Import {
        OpaqueFd, ///< by the descriptor (cl_khr_external_memory_opaque_fd): device memory
        HostPointer, ///< over Vulkan's mapping (CL_MEM_USE_HOST_PTR): a CPU device, host-visible memory
    };

    /// A buffer of memory both see: GL's buffer name and the device's buffer over the same bytes.
    class SharedBuffer {
    public:
        SharedBuffer() = default;
        SharedBuffer(SharedBuffer&&) noexcept;
        SharedBuffer& operator=(SharedBuffer&&) noexcept;
        ~SharedBuffer();
        GLuint gl() const { return gl_.id(); }
        const cl::Buffer& cl() const { return cl_; }

    private:
        friend class ExternalMemory;
        void reset();
        const ExternalMemory* owner_ = nullptr;
        cl::Buffer cl_;
        GlBuffer gl_;
        GLuint memoryObject_ = 0;
        uint64_t vkBuffer_ = 0, vkMemory_ = 0; // VkBuffer, VkDeviceMemory (non-dispatchable)
        bool mapped_ = false; // Import::HostPointer: Vulkan's mapping, under the device's buffer
    };

    /// "" where the current GL context and `cl` can share memory this way; else the path's
    /// refusal, naming what is missing. Asks the physical device, makes no Vulkan device: one that then fails to
    /// be made is the constructor's error.
    static std::string unavailable(const ClContext& cl);

    /// Throws hfx::Error with the same refusal where a part is missing.
    explicit ExternalMemory(ClContext& cl);
    ~ExternalMemory();
    ExternalMemory(const ExternalMemory&) = delete;
    ExternalMemory& operator=(const ExternalMemory&) = delete;

    /// `bytes` of memory both see. Throws hfx::Error naming the call that failed.
    SharedBuffer allocate(size_t bytes);
    /// The queue's hold on the buffers around the commands that use them (cl_khr_external_memory's
    /// acquire and release; nothing for a mapping).
    void acquire(std::span<const cl_mem> buffers) const;
    /// Returns once the device has let them go: GL may read them. Call after the queue has
    /// finished the commands that wrote them (over a mapping that is all it takes).
    void release(std::span<const cl_mem> buffers) const;
    /// "memory of Vulkan device 'NAME', imported by descriptor|over its mapping".
    std::string description() const;

private:
    struct Vulkan;
    ClContext& cl_;
    std::unique_ptr<Vulkan> vk_;
};

} // namespace hfx
