// The window side of `strata view`, built as a module (libstrata_view.so,
// host/window/) that view/viewer.cpp loads when the viewer starts, so that
// no other command loads GLFW, X11 or Dear ImGui. The module owns the GLFW
// window, its Vulkan swapchain and the ImGui panel; strata owns the device
// (vk::Context, with the window's surface), the render loop and the image.
// The interface is plain data and function pointers, as oiio/api.h's.
//
// Functions returning std::string return "" on success, else the error
// (one line).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace strata::view {

inline constexpr int kApiVersion = 1;

// The views the panel offers (Panel::view).
enum View : int { kViewColor = 0, kViewAlbedo, kViewNormal, kViewDepth, kViewDenoised, kViewCount };
inline constexpr const char* kViewNames[kViewCount] = {"colour", "albedo", "normal", "depth", "denoised"};

// What the panel shows, and the settings it edits (view, exposure,
// maxDepth, camera): present() writes the user's changes back.
struct Panel {
    std::uint32_t spp = 0;        // in the image shown
    std::uint32_t sppCap = 0;     // where accumulation stops
    double samplesPerSecond = 0.0;
    double seconds = 0.0;         // since the accumulation restarted
    std::string device, sampler, lightSampler, integrator;
    std::vector<std::string> cameras;  // the scene's cameras, then "free"
    int camera = 0;
    int view = kViewColor;
    float exposure = 0.0f;        // stops
    int maxDepth = 16;
    std::string status;           // one line under the figures (a file saved, ...)
    bool save = false;            // its buttons, pressed in this frame
    bool printCommand = false;
};

// What happened since the last poll.
struct Input {
    bool close = false;            // the window was closed (or requestClose)
    int width = 0, height = 0;     // its framebuffer now, pixels
    double orbitX = 0, orbitY = 0; // left-button drag outside the panel, pixels
    double panX = 0, panY = 0;     // right- or middle-button drag, pixels
    double zoom = 0;               // wheel steps (positive: towards the target)
    float fly[3] = {0, 0, 0};      // W/S forward, D/A right, E/Q up held: -1, 0 or 1 each
    bool save = false;             // F2 or Ctrl+S
    bool printCommand = false;     // P
    bool resetView = false;        // R
    bool nextCamera = false;       // C
};

// The device the window presents with, from strata's vk::Context.
struct Device {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
};

struct Window;  // the module's

struct Api {
    int version = kApiVersion;
    // Initialises GLFW and opens a window of width x height pixels; the
    // errors: no display, or no Vulkan presentation through GLFW.
    std::string (*open)(int width, int height, const std::string& title, Window** out);
    // The instance extensions its surface needs.
    std::vector<std::string> (*instanceExtensions)(Window* w);
    std::string (*createSurface)(Window* w, VkInstance instance, VkSurfaceKHR* out);
    // Its swapchain and ImGui on the device (after the Context exists).
    std::string (*attach)(Window* w, const Device& device);
    // Processes the window's events, waiting up to waitSeconds for one
    // when waitSeconds > 0.
    void (*poll)(Window* w, double waitSeconds, Input& input);
    // Shows `rgba` (width x height, 8-bit sRGB-encoded RGBA, row 0 at the
    // top) scaled to the window, with the panel over it; the panel's edits
    // are written to `panel`. `panelShown` false: the image alone. With
    // `capture`, what the window then shows, panel included, is read back
    // into it (RGBA, the window's size in captureWidth x captureHeight).
    std::string (*present)(Window* w, const std::uint8_t* rgba, int width, int height, Panel& panel, bool panelShown,
                           std::vector<std::uint8_t>* capture, int* captureWidth, int* captureHeight);
    // For scripts and tests: resize the window, or close it, as the user
    // would (the next poll sees it).
    void (*requestSize)(Window* w, int width, int height);
    void (*requestClose)(Window* w);
    // Releases the swapchain and ImGui's device objects (before the surface
    // and the device go), then, in close, the window and GLFW.
    void (*detach)(Window* w);
    void (*close)(Window* w);
};

}  // namespace strata::view

// The module's one exported symbol: its Api (util/module.h says why as const void*).
extern "C" const void* strata_view_api();
