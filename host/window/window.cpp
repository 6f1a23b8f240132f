// libstrata_view.so: the window of `strata view` (view/api.h): a GLFW
// window, its Vulkan swapchain, and a Dear ImGui panel drawn over the
// image. Each present copies the image (8-bit sRGB, from strata) into the
// acquired swapchain image, then draws the panel in a render pass that
// loads it. One frame in flight: the queue is strata's, shared with the
// render loop's submissions on the same thread.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include "view/api.h"
#include "window/panel.h"

namespace strata::view {

struct Window {
    GLFWwindow* glfw = nullptr;
    Device dev;
    bool imguiGlfw = false, imguiVulkan = false;
    // Events between polls (callbacks).
    double scroll = 0.0;
    std::vector<int> pressed;  // keys pressed (GLFW_KEY_*), with their mods folded in below
    bool ctrlS = false;
    double lastX = 0.0, lastY = 0.0;
    bool haveCursor = false;
    // The device side.
    VkRenderPass renderPass = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE, rendered = VK_NULL_HANDLE;
    VkDescriptorPool descriptors = VK_NULL_HANDLE;
    VkSurfaceFormatKHR format{};
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkExtent2D extent{0, 0};
    std::vector<VkImage> images;
    std::vector<VkImageView> views;
    std::vector<VkFramebuffer> framebuffers;
    bool stale = true;  // the swapchain must be made again (resized, out of date)
    bool readable = false;  // its images can be copied from (present's capture)
    VkBuffer staging = VK_NULL_HANDLE;
    VkDeviceMemory stagingMemory = VK_NULL_HANDLE;
    VkDeviceSize stagingBytes = 0;
    void* stagingMapped = nullptr;
};

namespace {

std::string gGlfwError;  // GLFW's last error, for messages

void onGlfwError(int, const char* description) { gGlfwError = description ? description : "unknown GLFW error"; }

std::string vkError(const char* what, VkResult r) { return std::string(what) + " failed (VkResult " + std::to_string(r) + ")"; }

#define TRY_VK(call)                                           \
    do {                                                       \
        const VkResult r_ = (call);                            \
        if (r_ != VK_SUCCESS) return vkError(#call, r_);       \
    } while (0)

void onScroll(GLFWwindow* g, double, double dy) {
    auto* w = static_cast<Window*>(glfwGetWindowUserPointer(g));
    if (!ImGui::GetCurrentContext() || !ImGui::GetIO().WantCaptureMouse) w->scroll += dy;
}

void onKey(GLFWwindow* g, int key, int, int action, int mods) {
    auto* w = static_cast<Window*>(glfwGetWindowUserPointer(g));
    if (action != GLFW_PRESS) return;
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
    if (key == GLFW_KEY_S && (mods & GLFW_MOD_CONTROL)) {
        w->ctrlS = true;
        return;
    }
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(g, GLFW_TRUE);
    w->pressed.push_back(key);
}

std::string openWindow(int width, int height, const std::string& title, Window** out) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) return "no display to open a window on (" + gGlfwError + ")";
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        return "GLFW finds no Vulkan loader and driver that can present to this display";
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    auto* w = new Window;
    w->glfw = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!w->glfw) {
        delete w;
        glfwTerminate();
        return "cannot open a window (" + gGlfwError + ")";
    }
    glfwSetWindowUserPointer(w->glfw, w);
    // Ours first: ImGui's callbacks call them after their own.
    glfwSetScrollCallback(w->glfw, onScroll);
    glfwSetKeyCallback(w->glfw, onKey);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // writes nothing unasked
    io.LogFilename = nullptr;
    ImGui::StyleColorsDark();
    w->imguiGlfw = ImGui_ImplGlfw_InitForVulkan(w->glfw, true);
    *out = w;
    return "";
}

std::vector<std::string> instanceExtensions(Window*) {
    std::uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    std::vector<std::string> out;
    for (std::uint32_t i = 0; i < count; ++i) out.push_back(names[i]);
    return out;
}

std::string createSurface(Window* w, VkInstance instance, VkSurfaceKHR* out) {
    const VkResult r = glfwCreateWindowSurface(instance, w->glfw, nullptr, out);
    if (r != VK_SUCCESS) return "cannot make a Vulkan surface for the window (" + gGlfwError + ")";
    return "";
}

void destroySwapchain(Window* w, bool keepHandle) {
    for (VkFramebuffer f : w->framebuffers) vkDestroyFramebuffer(w->dev.device, f, nullptr);
    for (VkImageView v : w->views) vkDestroyImageView(w->dev.device, v, nullptr);
    w->framebuffers.clear();
    w->views.clear();
    w->images.clear();
    if (!keepHandle && w->swapchain) {
        vkDestroySwapchainKHR(w->dev.device, w->swapchain, nullptr);
        w->swapchain = VK_NULL_HANDLE;
    }
}

// The swapchain at the window's framebuffer size (none while it is 0 x 0).
std::string makeSwapchain(Window* w) {
    vkDeviceWaitIdle(w->dev.device);
    VkSurfaceCapabilitiesKHR caps;
    TRY_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(w->dev.physical, w->dev.surface, &caps));
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(w->glfw, &fw, &fh);
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == 0xFFFFFFFFu) {
        extent.width = std::clamp<std::uint32_t>(fw, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp<std::uint32_t>(fh, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    destroySwapchain(w, true);
    if (extent.width == 0 || extent.height == 0) {  // minimised
        destroySwapchain(w, false);
        w->extent = extent;
        return "";
    }
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        return "the window's swapchain images cannot be copied to (no VK_IMAGE_USAGE_TRANSFER_DST_BIT)";
    std::uint32_t modeCount = 0;
    TRY_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(w->dev.physical, w->dev.surface, &modeCount, nullptr));
    std::vector<VkPresentModeKHR> modes(modeCount);
    TRY_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(w->dev.physical, w->dev.surface, &modeCount, modes.data()));
    // No vsync wait: the render loop, not the display, sets the pace.
    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;
    for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
        if (std::find(modes.begin(), modes.end(), m) != modes.end()) mode = m;
    std::uint32_t count = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = w->dev.surface;
    info.minImageCount = count;
    info.imageFormat = w->format.format;
    info.imageColorSpace = w->format.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    w->readable = (info.imageUsage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                            ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                            : caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha &
                                                                         -caps.supportedCompositeAlpha);
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = w->swapchain;
    VkSwapchainKHR made = VK_NULL_HANDLE;
    TRY_VK(vkCreateSwapchainKHR(w->dev.device, &info, nullptr, &made));
    if (w->swapchain) vkDestroySwapchainKHR(w->dev.device, w->swapchain, nullptr);
    w->swapchain = made;
    w->extent = extent;
    std::uint32_t n = 0;
    TRY_VK(vkGetSwapchainImagesKHR(w->dev.device, w->swapchain, &n, nullptr));
    w->images.resize(n);
    TRY_VK(vkGetSwapchainImagesKHR(w->dev.device, w->swapchain, &n, w->images.data()));
    for (VkImage image : w->images) {
        VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        v.image = image;
        v.viewType = VK_IMAGE_VIEW_TYPE_2D;
        v.format = w->format.format;
        v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        TRY_VK(vkCreateImageView(w->dev.device, &v, nullptr, &view));
        w->views.push_back(view);
        VkFramebufferCreateInfo f{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        f.renderPass = w->renderPass;
        f.attachmentCount = 1;
        f.pAttachments = &view;
        f.width = extent.width;
        f.height = extent.height;
        f.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        TRY_VK(vkCreateFramebuffer(w->dev.device, &f, nullptr, &fb));
        w->framebuffers.push_back(fb);
    }
    if (w->imguiVulkan) ImGui_ImplVulkan_SetMinImageCount(count);
    w->stale = false;
    return "";
}

std::uint32_t memoryType(const Device& d, std::uint32_t bits, VkMemoryPropertyFlags want) {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(d.physical, &props);
    for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want) return i;
    return UINT32_MAX;
}

std::string ensureStaging(Window* w, VkDeviceSize bytes) {
    if (w->stagingBytes >= bytes) return "";
    if (w->staging) {
        vkDestroyBuffer(w->dev.device, w->staging, nullptr);
        vkFreeMemory(w->dev.device, w->stagingMemory, nullptr);
        w->staging = VK_NULL_HANDLE;
        w->stagingMemory = VK_NULL_HANDLE;
        w->stagingBytes = 0;
    }
    VkBufferCreateInfo b{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    b.size = bytes;
    b.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;  // DST: capture
    TRY_VK(vkCreateBuffer(w->dev.device, &b, nullptr, &w->staging));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(w->dev.device, w->staging, &req);
    VkMemoryAllocateInfo a{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    a.allocationSize = req.size;
    a.memoryTypeIndex = memoryType(w->dev, req.memoryTypeBits,
                                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (a.memoryTypeIndex == UINT32_MAX) return "no host-visible memory for the window's image";
    TRY_VK(vkAllocateMemory(w->dev.device, &a, nullptr, &w->stagingMemory));
    TRY_VK(vkBindBufferMemory(w->dev.device, w->staging, w->stagingMemory, 0));
    TRY_VK(vkMapMemory(w->dev.device, w->stagingMemory, 0, VK_WHOLE_SIZE, 0, &w->stagingMapped));
    w->stagingBytes = bytes;
    return "";
}

std::string attach(Window* w, const Device& d) {
    w->dev = d;
    std::uint32_t formatCount = 0;
    TRY_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(d.physical, d.surface, &formatCount, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(formatCount);
    TRY_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(d.physical, d.surface, &formatCount, formats.data()));
    // UNORM: the image arrives sRGB-encoded, and ImGui's colours are too.
    bool found = false;
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
        for (const VkSurfaceFormatKHR& f : formats)
            if (!found && f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) w->format = f, found = true;
    if (!found) return "the window offers no 8-bit RGBA or BGRA swapchain format";

    VkAttachmentDescription color{};
    color.format = w->format.format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the image copied in before
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dep.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 1;
    rp.pAttachments = &color;
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    rp.dependencyCount = 1;
    rp.pDependencies = &dep;
    TRY_VK(vkCreateRenderPass(d.device, &rp, nullptr, &w->renderPass));

    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = d.queueFamily;
    TRY_VK(vkCreateCommandPool(d.device, &pool, nullptr, &w->pool));
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = w->pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    TRY_VK(vkAllocateCommandBuffers(d.device, &alloc, &w->cmd));
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    TRY_VK(vkCreateFence(d.device, &fence, nullptr, &w->fence));
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    TRY_VK(vkCreateSemaphore(d.device, &sem, nullptr, &w->acquired));
    TRY_VK(vkCreateSemaphore(d.device, &sem, nullptr, &w->rendered));
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4}};
    VkDescriptorPoolCreateInfo dp{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dp.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    dp.maxSets = 4;
    dp.poolSizeCount = 1;
    dp.pPoolSizes = sizes;
    TRY_VK(vkCreateDescriptorPool(d.device, &dp, nullptr, &w->descriptors));

    const std::string made = makeSwapchain(w);
    if (!made.empty()) return made;
    ImGui_ImplVulkan_InitInfo init{};
    init.Instance = d.instance;
    init.PhysicalDevice = d.physical;
    init.Device = d.device;
    init.QueueFamily = d.queueFamily;
    init.Queue = d.queue;
    init.DescriptorPool = w->descriptors;
    init.MinImageCount = 2;
    init.ImageCount = std::max<std::uint32_t>(2, static_cast<std::uint32_t>(w->images.size()));
    init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    if (!ImGui_ImplVulkan_Init(&init, w->renderPass)) return "Dear ImGui's Vulkan backend did not start";
    w->imguiVulkan = true;
    // The font atlas, uploaded once.
    TRY_VK(vkResetCommandBuffer(w->cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    TRY_VK(vkBeginCommandBuffer(w->cmd, &begin));
    ImGui_ImplVulkan_CreateFontsTexture(w->cmd);
    TRY_VK(vkEndCommandBuffer(w->cmd));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &w->cmd;
    TRY_VK(vkResetFences(d.device, 1, &w->fence));
    TRY_VK(vkQueueSubmit(d.queue, 1, &submit, w->fence));
    TRY_VK(vkWaitForFences(d.device, 1, &w->fence, VK_TRUE, UINT64_MAX));
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return "";
}

void poll(Window* w, double waitSeconds, Input& in) {
    if (waitSeconds > 0.0) glfwWaitEventsTimeout(waitSeconds);
    else glfwPollEvents();
    in.close = in.close || glfwWindowShouldClose(w->glfw);
    glfwGetFramebufferSize(w->glfw, &in.width, &in.height);
    const bool mouseFree = !ImGui::GetIO().WantCaptureMouse;
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(w->glfw, &x, &y);
    if (w->haveCursor && mouseFree) {
        const double dx = x - w->lastX, dy = y - w->lastY;
        if (glfwGetMouseButton(w->glfw, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) in.orbitX += dx, in.orbitY += dy;
        if (glfwGetMouseButton(w->glfw, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
            glfwGetMouseButton(w->glfw, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS)
            in.panX += dx, in.panY += dy;
    }
    w->lastX = x, w->lastY = y, w->haveCursor = true;
    in.zoom += w->scroll;
    w->scroll = 0.0;
    if (!ImGui::GetIO().WantCaptureKeyboard) {
        auto held = [&](int key) { return glfwGetKey(w->glfw, key) == GLFW_PRESS ? 1.0f : 0.0f; };
        const bool ctrl = held(GLFW_KEY_LEFT_CONTROL) + held(GLFW_KEY_RIGHT_CONTROL) > 0.0f;
        if (!ctrl) {
            in.fly[0] = held(GLFW_KEY_D) - held(GLFW_KEY_A);
            in.fly[1] = held(GLFW_KEY_E) - held(GLFW_KEY_Q);
            in.fly[2] = held(GLFW_KEY_W) - held(GLFW_KEY_S);
        }
    }
    for (int key : w->pressed) {
        if (key == GLFW_KEY_F2) in.save = true;
        if (key == GLFW_KEY_P) in.printCommand = true;
        if (key == GLFW_KEY_R) in.resetView = true;
        if (key == GLFW_KEY_C) in.nextCamera = true;
    }
    in.save = in.save || w->ctrlS;
    w->pressed.clear();
    w->ctrlS = false;
}

// The image into the staging buffer at the swapchain's size and byte order
// (nearest texel where the sizes differ, during a resize).
void stage(Window* w, const std::uint8_t* rgba, int width, int height) {
    const std::uint32_t W = w->extent.width, H = w->extent.height;
    auto* out = static_cast<std::uint8_t*>(w->stagingMapped);
    const bool bgra = w->format.format == VK_FORMAT_B8G8R8A8_UNORM;
    for (std::uint32_t y = 0; y < H; ++y) {
        const int sy = static_cast<int>((std::uint64_t(y) * height) / H);
        for (std::uint32_t x = 0; x < W; ++x) {
            const int sx = static_cast<int>((std::uint64_t(x) * width) / W);
            const std::uint8_t* s = rgba + (std::size_t(sy) * width + sx) * 4;
            std::uint8_t* d = out + (std::size_t(y) * W + x) * 4;
            d[0] = bgra ? s[2] : s[0];
            d[1] = s[1];
            d[2] = bgra ? s[0] : s[2];
            d[3] = 255;
        }
    }
}

std::string present(Window* w, const std::uint8_t* rgba, int width, int height, Panel& panel, bool panelShown,
                    std::vector<std::uint8_t>* capture, int* captureWidth, int* captureHeight) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(w->glfw, &fw, &fh);
    if (w->stale || fw != static_cast<int>(w->extent.width) || fh != static_cast<int>(w->extent.height)) {
        const std::string made = makeSwapchain(w);
        if (!made.empty()) return made;
    }
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    panel.save = panel.printCommand = false;
    if (panelShown) drawPanel(panel);
    ImGui::Render();
    if (!w->swapchain) return "";  // minimised: nothing to show
    TRY_VK(vkWaitForFences(w->dev.device, 1, &w->fence, VK_TRUE, UINT64_MAX));
    std::uint32_t index = 0;
    VkResult r = vkAcquireNextImageKHR(w->dev.device, w->swapchain, UINT64_MAX, w->acquired, VK_NULL_HANDLE, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        w->stale = true;
        return "";
    }
    if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) return vkError("vkAcquireNextImageKHR", r);
    if (capture && !w->readable) return "the window's swapchain images cannot be read back (no VK_IMAGE_USAGE_TRANSFER_SRC_BIT)";
    const std::string staged = ensureStaging(w, VkDeviceSize(w->extent.width) * w->extent.height * 4);
    if (!staged.empty()) return staged;
    stage(w, rgba, width, height);
    TRY_VK(vkResetFences(w->dev.device, 1, &w->fence));
    TRY_VK(vkResetCommandBuffer(w->cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    TRY_VK(vkBeginCommandBuffer(w->cmd, &begin));
    VkImageMemoryBarrier toCopy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    toCopy.srcAccessMask = 0;
    toCopy.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toCopy.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toCopy.srcQueueFamilyIndex = toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toCopy.image = w->images[index];
    toCopy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(w->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &toCopy);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {w->extent.width, w->extent.height, 1};
    vkCmdCopyBufferToImage(w->cmd, w->staging, w->images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    pass.renderPass = w->renderPass;
    pass.framebuffer = w->framebuffers[index];
    pass.renderArea.extent = w->extent;
    vkCmdBeginRenderPass(w->cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), w->cmd);
    vkCmdEndRenderPass(w->cmd);
    if (capture) {  // the image as presented, panel included, back into the staging buffer
        VkImageMemoryBarrier toRead = toCopy;
        toRead.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        toRead.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        toRead.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        toRead.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        vkCmdPipelineBarrier(w->cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                             nullptr, 0, nullptr, 1, &toRead);
        vkCmdCopyImageToBuffer(w->cmd, w->images[index], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w->staging, 1, &region);
        VkImageMemoryBarrier back = toRead;
        back.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        back.dstAccessMask = 0;
        back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        back.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        vkCmdPipelineBarrier(w->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0,
                             nullptr, 0, nullptr, 1, &back);
        VkBufferMemoryBarrier host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
        host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        host.buffer = w->staging;
        host.size = VK_WHOLE_SIZE;
        vkCmdPipelineBarrier(w->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1,
                             &host, 0, nullptr);
    }
    TRY_VK(vkEndCommandBuffer(w->cmd));
    // The acquire's wait: before the copy writes the image.
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &w->acquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &w->cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &w->rendered;
    TRY_VK(vkQueueSubmit(w->dev.queue, 1, &submit, w->fence));
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &w->rendered;
    info.swapchainCount = 1;
    info.pSwapchains = &w->swapchain;
    info.pImageIndices = &index;
    r = vkQueuePresentKHR(w->dev.queue, &info);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) w->stale = true;
    else if (r != VK_SUCCESS) return vkError("vkQueuePresentKHR", r);
    if (capture) {
        TRY_VK(vkWaitForFences(w->dev.device, 1, &w->fence, VK_TRUE, UINT64_MAX));
        const std::uint32_t W = w->extent.width, H = w->extent.height;
        const auto* in = static_cast<const std::uint8_t*>(w->stagingMapped);
        const bool bgra = w->format.format == VK_FORMAT_B8G8R8A8_UNORM;
        capture->resize(std::size_t(W) * H * 4);
        for (std::size_t i = 0; i < std::size_t(W) * H; ++i) {
            (*capture)[4 * i + 0] = in[4 * i + (bgra ? 2 : 0)];
            (*capture)[4 * i + 1] = in[4 * i + 1];
            (*capture)[4 * i + 2] = in[4 * i + (bgra ? 0 : 2)];
            (*capture)[4 * i + 3] = 255;
        }
        *captureWidth = int(W);
        *captureHeight = int(H);
    }
    return "";
}

void requestSize(Window* w, int width, int height) { glfwSetWindowSize(w->glfw, width, height); }

void requestClose(Window* w) { glfwSetWindowShouldClose(w->glfw, GLFW_TRUE); }

void detach(Window* w) {
    if (!w->dev.device) return;
    vkDeviceWaitIdle(w->dev.device);
    if (w->imguiVulkan) ImGui_ImplVulkan_Shutdown();
    w->imguiVulkan = false;
    destroySwapchain(w, false);
    if (w->staging) vkDestroyBuffer(w->dev.device, w->staging, nullptr);
    if (w->stagingMemory) vkFreeMemory(w->dev.device, w->stagingMemory, nullptr);
    if (w->descriptors) vkDestroyDescriptorPool(w->dev.device, w->descriptors, nullptr);
    if (w->acquired) vkDestroySemaphore(w->dev.device, w->acquired, nullptr);
    if (w->rendered) vkDestroySemaphore(w->dev.device, w->rendered, nullptr);
    if (w->fence) vkDestroyFence(w->dev.device, w->fence, nullptr);
    if (w->pool) vkDestroyCommandPool(w->dev.device, w->pool, nullptr);
    if (w->renderPass) vkDestroyRenderPass(w->dev.device, w->renderPass, nullptr);
    w->dev = Device{};
}

void close(Window* w) {
    if (!w) return;
    detach(w);
    if (w->imguiGlfw) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(w->glfw);
    glfwTerminate();
    delete w;
}

const Api kApi{kApiVersion, openWindow, instanceExtensions, createSurface, attach, poll, present,
               requestSize, requestClose, detach, close};

}  // namespace
}  // namespace strata::view

extern "C" __attribute__((visibility("default"))) const void* strata_view_api() {
    return &strata::view::kApi;
}
