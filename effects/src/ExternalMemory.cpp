#include "ExternalMemory.h"

#include "hfx/core/Error.h"

#define VK_NO_PROTOTYPES // every entry point through the loader opened at run time
#include <vulkan/vulkan.h>

#include <CL/cl_ext.h>

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <iomanip>
#include <sstream>

namespace hfx {
namespace {

using Uuid = std::array<unsigned char, 16>;

std::string hex(const Uuid& u) {
    std::ostringstream s;
    for (unsigned char c : u) s << std::hex << std::setw(2) << std::setfill('0') << int(c);
    return s.str();
}

bool hasExtension(const std::string& list, std::string_view name) {
    std::istringstream words(list);
    for (std::string w; words >> w;)
        if (w == name) return true;
    return false;
}

// clCreateBufferWithProperties is OpenCL 3.0 (the build targets 1.2's headers and loaders):
// looked up in the loader, as the extension's own entry points are in the platform.
using CreateBufferWithProperties = cl_mem(CL_API_CALL*)(cl_context, const cl_ulong*, cl_mem_flags, size_t, void*,
                                                         cl_int*);
using EnqueueExternal = cl_int(CL_API_CALL*)(cl_command_queue, cl_uint, const cl_mem*, cl_uint, const cl_event*,
                                             cl_event*);

/// The memory GL's buffers lie in is this much larger than the buffer: Mesa 22's llvmpipe refuses a
/// GL buffer exactly as large as its memory object (GL_OUT_OF_MEMORY), one a page smaller it takes.
constexpr VkDeviceSize kSlack = 4096;

// The device's entry points ExternalMemory calls, each loaded by vkGetDeviceProcAddr.
#define HFX_VK_DEVICE_FUNCTIONS(X)                                                                 \
    X(vkDestroyDevice) X(vkCreateBuffer) X(vkDestroyBuffer) X(vkGetBufferMemoryRequirements)      \
    X(vkAllocateMemory) X(vkFreeMemory) X(vkBindBufferMemory) X(vkMapMemory) X(vkUnmapMemory)     \
    X(vkGetMemoryFdKHR)

// The instance's entry points ExternalMemory calls, each loaded by vkGetInstanceProcAddr.
#define HFX_VK_INSTANCE_FUNCTIONS(X)                                                               \
    X(vkEnumeratePhysicalDevices) X(vkGetPhysicalDeviceProperties2)                                \
    X(vkGetPhysicalDeviceMemoryProperties) X(vkEnumerateDeviceExtensionProperties)                 \
    X(vkGetPhysicalDeviceExternalBufferProperties) X(vkCreateDevice) X(vkGetDeviceProcAddr)

/// The Vulkan loader and one instance for the process, made when first asked for and kept to its
/// end (never unloaded: a loader unloads its drivers with their last instance, and making them
/// again for every question would cost as much again), or why there is none.
struct VulkanInstance {
    std::string failure; ///< "" where there is an instance
    VkInstance instance = VK_NULL_HANDLE;
#define HFX_VK_MEMBER(name) PFN_##name name = nullptr;
    HFX_VK_INSTANCE_FUNCTIONS(HFX_VK_MEMBER)
#undef HFX_VK_MEMBER

    static const VulkanInstance& get() {
        static const VulkanInstance* const one = new VulkanInstance(); // thread-safe, kept
        return *one;
    }

private:
    VulkanInstance() {
        void* library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!library) {
            failure = "no Vulkan loader (libvulkan.so.1) to allocate the memory with";
            return;
        }
        const auto getProc = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library, "vkGetInstanceProcAddr"));
        if (!getProc) {
            failure = "libvulkan.so.1 has no vkGetInstanceProcAddr";
            return;
        }
        const auto version = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
            getProc(VK_NULL_HANDLE, "vkEnumerateInstanceVersion"));
        uint32_t loader = VK_API_VERSION_1_0;
        if (version) version(&loader);
        if (loader < VK_API_VERSION_1_1) {
            failure = "the Vulkan loader is older than 1.1 (device UUIDs, external memory)";
            return;
        }
        const VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                                    .pApplicationName = "hfx",
                                    .apiVersion = VK_API_VERSION_1_1};
        const VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
        const auto create = reinterpret_cast<PFN_vkCreateInstance>(getProc(VK_NULL_HANDLE, "vkCreateInstance"));
        if (const VkResult r = create ? create(&info, nullptr, &instance) : VK_ERROR_INITIALIZATION_FAILED;
            r != VK_SUCCESS) {
            failure = str("no Vulkan driver (vkCreateInstance: VkResult ", int(r), ")");
            instance = VK_NULL_HANDLE;
            return;
        }
        std::string missing;
#define HFX_VK_LOAD(name)                                                                          \
    name = reinterpret_cast<PFN_##name>(getProc(instance, #name));                                 \
    if (!name) missing += str(missing.empty() ? "" : ", ", #name);
        HFX_VK_INSTANCE_FUNCTIONS(HFX_VK_LOAD)
#undef HFX_VK_LOAD
        if (!missing.empty()) failure = str("the Vulkan instance lacks 1.1's ", missing);
    }
};

} // namespace

struct ExternalMemory::Vulkan {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::string name;
    Import import = Import::OpaqueFd;
    bool dedicated = false; ///< the driver wants the memory dedicated to its buffer
    VkPhysicalDeviceMemoryProperties memory{};
    // The device's entry points, by their Vulkan names.
#define HFX_VK_MEMBER(name) PFN_##name name = nullptr;
    HFX_VK_DEVICE_FUNCTIONS(HFX_VK_MEMBER)
#undef HFX_VK_MEMBER
    // OpenCL's.
    CreateBufferWithProperties createClBuffer = nullptr;
    EnqueueExternal acquire = nullptr, release = nullptr;

    ~Vulkan() {
        if (device && vkDestroyDevice) vkDestroyDevice(device, nullptr);
    }

    /// The Vulkan device GL draws with, ready to export memory that `cl` can import; null with
    /// `why` saying what is missing. A probe finds the physical device and checks what it offers,
    /// but makes no VkDevice (and returns null with `why` empty where all is there).
    static std::unique_ptr<Vulkan> open(const ClContext& cl, std::string& why, bool probe = false);
};

std::unique_ptr<ExternalMemory::Vulkan> ExternalMemory::Vulkan::open(const ClContext& cl, std::string& why,
                                                                     bool probe) {
    const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (!GLAD_GL_EXT_memory_object || !GLAD_GL_EXT_memory_object_fd) {
        why = str("GL (", renderer, ") does not import memory (GL_EXT_memory_object_fd)");
        return nullptr;
    }
    Uuid glUuid{};
    // An error the caller left is not this query's: the first H200 run read a GlStateGuard's
    // GL_INVALID_VALUE here and blamed the UUID.
    while (glGetError() != GL_NO_ERROR) {}
    glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, glUuid.data());
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        why = str("GL (", renderer, ") did not say its device's UUID (", glErrorName(e), ")");
        return nullptr;
    }

    auto vk = std::make_unique<Vulkan>();
    const cl::Device& device = cl.device();
    const std::string clExtensions = device.getInfo<CL_DEVICE_EXTENSIONS>();
    Uuid clUuid{};
    if (hasExtension(clExtensions, "cl_khr_external_memory_opaque_fd") &&
        hasExtension(clExtensions, "cl_khr_device_uuid")) {
        vk->import = Import::OpaqueFd;
        if (const cl_int e = clGetDeviceInfo(device(), CL_DEVICE_UUID_KHR, clUuid.size(), clUuid.data(), nullptr);
            e != CL_SUCCESS) {
            why = str(cl.description(), " did not say its UUID (CL error ", e, ")");
            return nullptr;
        }
        vk->createClBuffer =
            reinterpret_cast<CreateBufferWithProperties>(dlsym(RTLD_DEFAULT, "clCreateBufferWithProperties"));
        const cl_platform_id platform = device.getInfo<CL_DEVICE_PLATFORM>();
        vk->acquire = reinterpret_cast<EnqueueExternal>(
            clGetExtensionFunctionAddressForPlatform(platform, "clEnqueueAcquireExternalMemObjectsKHR"));
        vk->release = reinterpret_cast<EnqueueExternal>(
            clGetExtensionFunctionAddressForPlatform(platform, "clEnqueueReleaseExternalMemObjectsKHR"));
        if (!vk->createClBuffer || !vk->acquire || !vk->release) {
            why = str("the OpenCL loader or ", cl.description(), " lacks clCreateBufferWithProperties or "
                      "cl_khr_external_memory's acquire and release");
            return nullptr;
        }
    } else if (device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>()) {
        vk->import = Import::HostPointer;
    } else {
        why = str(cl.description(), " imports no external memory (cl_khr_external_memory_opaque_fd with "
                  "cl_khr_device_uuid) and shares no host memory");
        return nullptr;
    }

    const VulkanInstance& in = VulkanInstance::get();
    if (!in.failure.empty()) {
        why = in.failure;
        return nullptr;
    }

    // GL's device among Vulkan's (and the compute device's, where it imports by descriptor).
    uint32_t count = 0;
    in.vkEnumeratePhysicalDevices(in.instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    in.vkEnumeratePhysicalDevices(in.instance, &count, devices.data());
    std::string seen;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceIDProperties id{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
        VkPhysicalDeviceProperties2 p{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &id};
        in.vkGetPhysicalDeviceProperties2(d, &p);
        Uuid u;
        std::copy(std::begin(id.deviceUUID), std::end(id.deviceUUID), u.begin());
        seen += str(seen.empty() ? "" : ", ", "'", p.properties.deviceName, "' ", hex(u));
        if (u == glUuid && !vk->physical) {
            vk->physical = d;
            vk->name = p.properties.deviceName;
        }
    }
    if (!vk->physical) {
        why = str("no Vulkan device is GL's (", renderer, ", device UUID ", hex(glUuid), "; Vulkan has ",
                  seen.empty() ? "none" : seen, ")");
        return nullptr;
    }
    if (vk->import == Import::OpaqueFd && clUuid != glUuid) {
        why = str(cl.description(), " is not the device GL draws with (UUIDs ", hex(clUuid), " and ", hex(glUuid), ")");
        return nullptr;
    }
    uint32_t extensions = 0;
    in.vkEnumerateDeviceExtensionProperties(vk->physical, nullptr, &extensions, nullptr);
    std::vector<VkExtensionProperties> available(extensions);
    in.vkEnumerateDeviceExtensionProperties(vk->physical, nullptr, &extensions, available.data());
    if (std::none_of(available.begin(), available.end(), [](const VkExtensionProperties& e) {
            return std::strcmp(e.extensionName, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME) == 0;
        })) {
        why = str("Vulkan device '", vk->name, "' does not export memory (", VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME,
                  ")");
        return nullptr;
    }
    const VkPhysicalDeviceExternalBufferInfo bufferInfo{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_BUFFER_INFO,
        .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        .handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT};
    VkExternalBufferProperties external{.sType = VK_STRUCTURE_TYPE_EXTERNAL_BUFFER_PROPERTIES};
    in.vkGetPhysicalDeviceExternalBufferProperties(vk->physical, &bufferInfo, &external);
    const VkExternalMemoryFeatureFlags features = external.externalMemoryProperties.externalMemoryFeatures;
    if (!(features & VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT)) {
        why = str("Vulkan device '", vk->name, "' exports no buffer memory as a file descriptor");
        return nullptr;
    }
    vk->dedicated = (features & VK_EXTERNAL_MEMORY_FEATURE_DEDICATED_ONLY_BIT) != 0;
    in.vkGetPhysicalDeviceMemoryProperties(vk->physical, &vk->memory);
    // A mapping needs memory the host sees, coherent: find out now, not at the first allocation.
    if (vk->import == Import::HostPointer) {
        bool visible = false;
        for (uint32_t i = 0; i < vk->memory.memoryTypeCount; ++i)
            visible |= (vk->memory.memoryTypes[i].propertyFlags &
                        (VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) ==
                       (VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        if (!visible) {
            why = str(cl.description(), " would take the memory over a mapping, and Vulkan device '", vk->name,
                      "' has none the host sees");
            return nullptr;
        }
    }
    if (probe) return nullptr;

    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queue{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                        .queueFamilyIndex = 0,
                                        .queueCount = 1,
                                        .pQueuePriorities = &priority};
    const char* const enabled[] = {VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME};
    const VkDeviceCreateInfo deviceInfo{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                        .queueCreateInfoCount = 1,
                                        .pQueueCreateInfos = &queue,
                                        .enabledExtensionCount = 1,
                                        .ppEnabledExtensionNames = enabled};
    if (const VkResult r = in.vkCreateDevice(vk->physical, &deviceInfo, nullptr, &vk->device); r != VK_SUCCESS) {
        why = str("vkCreateDevice on '", vk->name, "' failed (VkResult ", int(r), ")");
        vk->device = VK_NULL_HANDLE;
        return nullptr;
    }
    std::string missing;
#define HFX_VK_LOAD(name)                                                                          \
    vk->name = reinterpret_cast<PFN_##name>(in.vkGetDeviceProcAddr(vk->device, #name));            \
    if (!vk->name) missing += str(missing.empty() ? "" : ", ", #name);
    HFX_VK_DEVICE_FUNCTIONS(HFX_VK_LOAD)
#undef HFX_VK_LOAD
    if (!missing.empty()) {
        why = str("Vulkan device '", vk->name, "' lacks ", missing);
        return nullptr;
    }
    return vk;
}

namespace {
/// The refusal of the path, saying what is missing; "" where nothing is.
std::string refusal(const std::string& why) {
    return why.empty() ? "" : str("the external-memory transfer path is not available here: ", why);
}
} // namespace

std::string ExternalMemory::unavailable(const ClContext& cl) {
    std::string why;
    Vulkan::open(cl, why, true);
    return refusal(why);
}

ExternalMemory::ExternalMemory(ClContext& cl) : cl_(cl) {
    std::string why;
    vk_ = Vulkan::open(cl, why);
    if (!vk_) throw Error(refusal(why));
}

ExternalMemory::~ExternalMemory() = default;

std::string ExternalMemory::description() const {
    return str("memory of Vulkan device '", vk_->name, "', imported ",
               vk_->import == Import::OpaqueFd ? "by descriptor" : "over its mapping");
}

ExternalMemory::SharedBuffer ExternalMemory::allocate(size_t bytes) {
    Vulkan& vk = *vk_;
    SharedBuffer b;
    b.owner_ = this;
    const VkExternalMemoryBufferCreateInfo external{.sType = VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO,
                                                    .handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT};
    const VkBufferCreateInfo bufferInfo{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                                        .pNext = &external,
                                        .size = VkDeviceSize(bytes) + kSlack,
                                        .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    VkBuffer buffer = VK_NULL_HANDLE;
    if (const VkResult r = vk.vkCreateBuffer(vk.device, &bufferInfo, nullptr, &buffer); r != VK_SUCCESS)
        throw Error(str("external memory: vkCreateBuffer of ", bytes, " bytes failed (VkResult ", int(r), ")"));
    b.vkBuffer_ = reinterpret_cast<uint64_t>(buffer);
    VkMemoryRequirements need{};
    vk.vkGetBufferMemoryRequirements(vk.device, buffer, &need);
    // Device memory where the device imports by descriptor; memory the host sees where it maps.
    const VkMemoryPropertyFlags wanted =
        vk.import == Import::OpaqueFd ? VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)
                                      : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = vk.memory.memoryTypeCount;
    for (uint32_t i = 0; i < vk.memory.memoryTypeCount && type == vk.memory.memoryTypeCount; ++i)
        if ((need.memoryTypeBits >> i & 1u) && (vk.memory.memoryTypes[i].propertyFlags & wanted) == wanted) type = i;
    if (type == vk.memory.memoryTypeCount)
        throw Error(str("external memory: Vulkan device '", vk.name, "' offers no ",
                        vk.import == Import::OpaqueFd ? "device-local" : "host-visible, coherent",
                        " memory type for an exported buffer"));
    const VkMemoryDedicatedAllocateInfo dedicated{.sType = VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO,
                                                  .buffer = buffer};
    const VkExportMemoryAllocateInfo exported{.sType = VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO,
                                              .pNext = vk.dedicated ? &dedicated : nullptr,
                                              .handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT};
    const VkMemoryAllocateInfo allocation{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                          .pNext = &exported,
                                          .allocationSize = need.size,
                                          .memoryTypeIndex = type};
    VkDeviceMemory memory = VK_NULL_HANDLE;
    if (const VkResult r = vk.vkAllocateMemory(vk.device, &allocation, nullptr, &memory); r != VK_SUCCESS)
        throw Error(str("external memory: vkAllocateMemory of ", need.size, " bytes on '", vk.name,
                        "' failed (VkResult ", int(r), ")"));
    b.vkMemory_ = reinterpret_cast<uint64_t>(memory);
    if (const VkResult r = vk.vkBindBufferMemory(vk.device, buffer, memory, 0); r != VK_SUCCESS)
        throw Error(str("external memory: vkBindBufferMemory failed (VkResult ", int(r), ")"));
    auto descriptor = [&] {
        const VkMemoryGetFdInfoKHR info{.sType = VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR,
                                        .memory = memory,
                                        .handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT};
        int fd = -1;
        if (const VkResult r = vk.vkGetMemoryFdKHR(vk.device, &info, &fd); r != VK_SUCCESS)
            throw Error(str("external memory: vkGetMemoryFdKHR failed (VkResult ", int(r), ")"));
        return fd;
    };

    // GL: a memory object over the descriptor (GL owns it once imported), a buffer in it.
    glCreateMemoryObjectsEXT(1, &b.memoryObject_);
    detail::glCheck("glCreateMemoryObjectsEXT", __FILE__, __LINE__);
    if (vk.dedicated) {
        const GLint yes = GL_TRUE;
        glMemoryObjectParameterivEXT(b.memoryObject_, GL_DEDICATED_MEMORY_OBJECT_EXT, &yes);
    }
    const int glFd = descriptor();
    glImportMemoryFdEXT(b.memoryObject_, GLuint64(need.size), GL_HANDLE_TYPE_OPAQUE_FD_EXT, glFd);
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        close(glFd); // not taken
        throw Error(str("external memory: glImportMemoryFdEXT of ", need.size, " bytes failed (", glErrorName(e), ")"));
    }
    b.gl_ = GlBuffer::create();
    glNamedBufferStorageMemEXT(b.gl_.id(), GLsizeiptr(bytes), b.memoryObject_, 0);
    detail::glCheck("glNamedBufferStorageMemEXT", __FILE__, __LINE__);

    // The compute device: by its own descriptor, or over the mapping.
    if (vk.import == Import::OpaqueFd) {
        const int clFd = descriptor();
        const cl_ulong properties[] = {CL_EXTERNAL_MEMORY_HANDLE_OPAQUE_FD_KHR,
                                       cl_ulong(clFd),
                                       CL_DEVICE_HANDLE_LIST_KHR,
                                       cl_ulong(reinterpret_cast<uintptr_t>(cl_.device()())),
                                       CL_DEVICE_HANDLE_LIST_END_KHR,
                                       0};
        cl_int error = CL_SUCCESS;
        const cl_mem m = vk.createClBuffer(cl_.context()(), properties, CL_MEM_READ_WRITE, bytes, nullptr, &error);
        if (!m || error != CL_SUCCESS) {
            close(clFd);
            throw Error(str("external memory: clCreateBufferWithProperties over a Vulkan descriptor failed (CL error ",
                            error, ")"));
        }
        // A successful import hands the descriptor to the implementation (OpenCL 3.0, 5.5.2.1 "File
        // descriptor handle types"): the application must not touch it again, so it is not closed here.
        b.cl_ = cl::Buffer(m); // takes the reference
    } else {
        void* mapped = nullptr;
        if (const VkResult r = vk.vkMapMemory(vk.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped); r != VK_SUCCESS)
            throw Error(str("external memory: vkMapMemory failed (VkResult ", int(r), ")"));
        b.mapped_ = true;
        clGuard("making a device buffer over the shared memory's mapping",
                [&] { b.cl_ = cl::Buffer(cl_.context(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, bytes, mapped); });
    }
    return b;
}

void ExternalMemory::acquire(std::span<const cl_mem> buffers) const {
    if (vk_->import != Import::OpaqueFd || buffers.empty()) return;
    const cl_int e = vk_->acquire(cl_.queue()(), cl_uint(buffers.size()), buffers.data(), 0, nullptr, nullptr);
    if (e != CL_SUCCESS)
        throw Error(str("external memory: clEnqueueAcquireExternalMemObjectsKHR failed (CL error ", e, ")"));
}

void ExternalMemory::release(std::span<const cl_mem> buffers) const {
    if (vk_->import == Import::OpaqueFd && !buffers.empty()) {
        cl_event done = nullptr;
        const cl_int e = vk_->release(cl_.queue()(), cl_uint(buffers.size()), buffers.data(), 0, nullptr, &done);
        if (e != CL_SUCCESS)
            throw Error(str("external memory: clEnqueueReleaseExternalMemObjectsKHR failed (CL error ", e, ")"));
        const cl_int w = clWaitForEvents(1, &done);
        clReleaseEvent(done);
        if (w != CL_SUCCESS) throw Error(str("external memory: waiting for the release failed (CL error ", w, ")"));
    }
    // Over a mapping there is nothing to release: the caller has waited for the queue's frame
    // marker, behind the copies (an in-order queue).
}

ExternalMemory::SharedBuffer::SharedBuffer(SharedBuffer&& o) noexcept { *this = std::move(o); }

ExternalMemory::SharedBuffer& ExternalMemory::SharedBuffer::operator=(SharedBuffer&& o) noexcept {
    if (this != &o) {
        reset();
        owner_ = std::exchange(o.owner_, nullptr);
        cl_ = std::move(o.cl_);
        gl_ = std::move(o.gl_);
        memoryObject_ = std::exchange(o.memoryObject_, 0);
        vkBuffer_ = std::exchange(o.vkBuffer_, 0);
        vkMemory_ = std::exchange(o.vkMemory_, 0);
        mapped_ = std::exchange(o.mapped_, false);
    }
    return *this;
}

ExternalMemory::SharedBuffer::~SharedBuffer() { reset(); }

void ExternalMemory::SharedBuffer::reset() {
    if (!owner_) return;
    const Vulkan& vk = *owner_->vk_;
    cl_ = cl::Buffer(); // the device's view first, then GL's, then the memory under both
    gl_.reset();
    if (memoryObject_) glDeleteMemoryObjectsEXT(1, &memoryObject_);
    if (vkBuffer_) vk.vkDestroyBuffer(vk.device, reinterpret_cast<VkBuffer>(vkBuffer_), nullptr);
    if (vkMemory_) {
        const auto memory = reinterpret_cast<VkDeviceMemory>(vkMemory_);
        if (mapped_) vk.vkUnmapMemory(vk.device, memory);
        vk.vkFreeMemory(vk.device, memory, nullptr);
    }
    owner_ = nullptr;
    memoryObject_ = 0;
    vkBuffer_ = vkMemory_ = 0;
    mapped_ = false;
}

} // namespace hfx
