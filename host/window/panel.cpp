// The window module's panel (Dear ImGui): the figures of view/api.h's Panel
// and the settings it edits.
#include "window/panel.h"

#include <imgui.h>

namespace strata::view {

void drawPanel(Panel& p) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("strata", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushItemWidth(110.0f);
    ImGui::Text("%u / %u spp", p.spp, p.sppCap);
    ImGui::Text("%.2f Msamples/s, %.1f s", p.samplesPerSecond * 1e-6, p.seconds);
    ImGui::TextUnformatted(p.device.c_str());
    ImGui::Text("%s, %s sampler", p.integrator.c_str(), p.sampler.c_str());
    ImGui::Text("light sampler: %s", p.lightSampler.c_str());
    ImGui::SliderInt("max depth", &p.maxDepth, 1, 64);
    ImGui::Combo("view", &p.view, kViewNames, kViewCount);
    ImGui::SliderFloat("exposure", &p.exposure, -8.0f, 8.0f, "%.1f stops");
    if (!p.cameras.empty()) {
        std::vector<const char*> names;
        for (const std::string& c : p.cameras) names.push_back(c.c_str());
        ImGui::Combo("camera", &p.camera, names.data(), static_cast<int>(names.size()));
    }
    p.save = ImGui::Button("save (F2)");
    ImGui::SameLine();
    p.printCommand = ImGui::Button("command (P)");
    if (!p.status.empty()) ImGui::TextUnformatted(p.status.c_str());
    ImGui::TextDisabled("drag orbit, right pan, wheel zoom");
    ImGui::TextDisabled("WASDQE fly, R reset, C camera");
    ImGui::PopItemWidth();
    ImGui::End();
}

}  // namespace strata::view
