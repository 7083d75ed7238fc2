#include "ui.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>

namespace anyphys::testbed {
namespace {

template <class E>
bool enumCombo(const char* label, std::optional<E>& value, const char* unsetName) {
    std::string current = value ? std::string(toString(*value)) : unsetName;
    bool changed = false;
    if (ImGui::BeginCombo(label, current.c_str())) {
        if (ImGui::Selectable(unsetName, !value)) {
            value.reset();
            changed = true;
        }
        for (const auto& [e, name] : EnumNames<E>::values)
            if (ImGui::Selectable(std::string(name).c_str(), value && *value == e)) {
                value = e;
                changed = true;
            }
        ImGui::EndCombo();
    }
    return changed;
}

// An optional int: a checkbox to set it, a slider when set.
bool optionalInt(const char* label, std::optional<int>& value, int fallback, int lo, int hi) {
    bool set = value.has_value();
    bool changed = false;
    ImGui::PushID(label);
    if (ImGui::Checkbox("##set", &set)) {
        value = set ? std::optional<int>(fallback) : std::nullopt;
        changed = true;
    }
    ImGui::SameLine();
    if (value) {
        changed |= ImGui::SliderInt(label, &*value, lo, hi);
    } else {
        ImGui::TextDisabled("%s: scene / backend default", label);
    }
    ImGui::PopID();
    return changed;
}

// "ok", "FAIL", or "known" for a miss the backend declares within its ceiling (as `anyphys
// compare` and `anyphys hardcases` judge it).
std::string verdict(const View& v) {
    if (v.checkPasses()) return "ok";
    const Capabilities caps = backendInfo(v.backend).capabilities;
    if (!v.check->criterion.empty() && caps.knownDeviations.count(v.check->criterion)) {
        const auto ceiling = caps.deviationCeilings.find(v.check->criterion);
        if (ceiling == caps.deviationCeilings.end() || v.checkValue <= ceiling->second)
            return "known";
    }
    return "FAIL";
}

std::string checkText(const View& v) {
    if (!v.check) return "";
    char text[256];
    std::snprintf(text, sizeof text, "%s %.4g %s  %s (%g +- %g)", v.check->label.c_str(), v.checkValue, v.check->unit.c_str(),
                  verdict(v).c_str(), v.check->expected, v.check->tolerance);
    return text;
}

}  // namespace

void drawControlPanel(UiState& ui, const Views& views) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("anyphys testbed");

    if (ImGui::Button(ui.paused ? "Play (P)" : "Pause (P)")) ui.paused = !ui.paused;
    ImGui::SameLine();
    if (ImGui::Button("Step (O)")) ui.stepOnce = true;
    ImGui::SameLine();
    if (ImGui::Button("Reset (R)")) ui.reset = true;
    ImGui::SameLine();
    if (ImGui::Button("Ball (B)")) ui.shoot = true;
    ImGui::SliderFloat("time scale", &ui.timeScale, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);

    if (ImGui::CollapsingHeader("Scene and backends", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (!ui.sceneNames.empty()) {
            ui.sceneIndex = std::clamp(ui.sceneIndex, 0, static_cast<int>(ui.sceneNames.size()) - 1);
            if (ImGui::BeginCombo("scene", ui.sceneNames[ui.sceneIndex].c_str())) {
                for (int i = 0; i < static_cast<int>(ui.sceneNames.size()); ++i)
                    if (ImGui::Selectable(ui.sceneNames[i].c_str(), i == ui.sceneIndex)) {
                        ui.sceneIndex = i;
                        ui.openScene = ui.sceneNames[i];
                        ui.reopen = true;
                    }
                ImGui::EndCombo();
            }
        }
        ImGui::InputText("file", &ui.sceneFile);
        ImGui::SameLine();
        if (ImGui::Button("Open") && !ui.sceneFile.empty()) {
            ui.openScene = ui.sceneFile;
            ui.reopen = true;
        }
        for (std::size_t i = 0; i < ui.allBackends.size(); ++i) {
            bool on = ui.selected[i];
            if (ImGui::Checkbox(ui.allBackends[i].c_str(), &on)) {
                ui.selected[i] = on;
                ui.openScene = views.source().name;
                ui.reopen = true;
            }
            if (i + 1 < ui.allBackends.size()) ImGui::SameLine();
        }
        ImGui::TextWrapped("%s", views.source().description.c_str());
    }

    if (ImGui::CollapsingHeader("Settings (every view, live)", ImGuiTreeNodeFlags_DefaultOpen)) {
        LiveSettings& s = ui.edit;
        bool changed = false;
        {
            bool set = s.timeStep.has_value();
            if (ImGui::Checkbox("##dt", &set)) {
                s.timeStep = set ? std::optional<double>(1.0 / 60.0) : std::nullopt;
                changed = true;
            }
            ImGui::SameLine();
            if (s.timeStep) {
                float hertz = static_cast<float>(1.0 / *s.timeStep);
                if (ImGui::SliderFloat("step rate (Hz)", &hertz, 15.0f, 960.0f, "%.0f", ImGuiSliderFlags_Logarithmic)) {
                    s.timeStep = 1.0 / hertz;
                    changed = true;
                }
            } else {
                ImGui::TextDisabled("step: the scene's");
            }
        }
        changed |= optionalInt("substeps", s.substeps, 4, 1, 32);
        changed |= optionalInt("iterations", s.iterations, 10, 1, 100);
        changed |= enumCombo("solver", s.solver, "backend default");
        changed |= enumCombo("integrator", s.integrator, "scene's");
        bool setEffects = s.effects.has_value();
        if (ImGui::Checkbox("set effects (else derived from the scene)", &setEffects)) {
            if (setEffects) {
                Effects now;
                for (const View& v : views.views())
                    if (v.world) {
                        now = v.world->activeEffects();
                        break;
                    }
                s.effects = now;
            } else {
                s.effects.reset();
            }
            changed = true;
        }
        if (s.effects) {
            int column = 0;
            for (const auto& n : kEffectNames) {
                bool on = s.effects->has(n.effect);
                if (ImGui::Checkbox(std::string(n.name).c_str(), &on)) {
                    on ? s.effects->add(n.effect) : s.effects->remove(n.effect);
                    changed = true;
                }
                if (++column % 3 != 0) ImGui::SameLine();
            }
            ImGui::NewLine();
        }
        if (changed) ui.settingsChanged = true;
    }

    if (ImGui::CollapsingHeader("Draw", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Checkbox("contacts", &ui.draw.contacts);
        ImGui::SameLine();
        ImGui::Checkbox("joints", &ui.draw.joints);
        ImGui::SameLine();
        ImGui::Checkbox("bounds", &ui.draw.bounds);
        ImGui::SameLine();
        ImGui::Checkbox("sleep", &ui.draw.sleep);
        ImGui::Checkbox("plots", &ui.showPlots);
    }
    ImGui::TextDisabled("left: drag a body / orbit, right: orbit, middle: pan, wheel: zoom");
    if (!ui.message.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", ui.message.c_str());
    ImGui::End();
}

void drawViewLabels(const Views& views, const std::vector<Rect>& rects, float scale) {
    for (std::size_t i = 0; i < views.views().size() && i < rects.size(); ++i) {
        const View& v = views.views()[i];
        const Rect& r = rects[i];
        ImGui::SetNextWindowPos(ImVec2((r.x + r.w) / scale - 8, r.y / scale + 8), ImGuiCond_Always, ImVec2(1, 0));
        ImGui::SetNextWindowBgAlpha(0.6f);
        const std::string id = "##view" + std::to_string(i);
        ImGui::Begin(id.c_str(), nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
        ImGui::Text("%s  %s", v.backend.c_str(), v.sceneName.c_str());
        if (!v.error.empty()) {
            ImGui::PushTextWrapPos(r.w / scale * 0.8f);
            ImGui::TextColored(ImVec4(1, 0.45f, 0.45f, 1), "%s", v.error.c_str());
            ImGui::PopTextWrapPos();
        } else {
            ImGui::Text("t %.2f s  step %.3f ms (mean %.3f)  %zu bodies", v.time(), v.lastStepMs, v.meanStepMs, v.bodies.size());
            if (v.check) {
                const std::string judged = verdict(v);
                const ImVec4 colour = judged == "ok"      ? ImVec4(0.5f, 1, 0.5f, 1)
                                      : judged == "known" ? ImVec4(1, 0.85f, 0.4f, 1)
                                                          : ImVec4(1, 0.5f, 0.4f, 1);
                ImGui::TextColored(colour, "%s", checkText(v).c_str());
            }
        }
        ImGui::End();
    }
}

void drawPlots(const Views& views, float windowWidth, float windowHeight) {
    const float height = 150.0f;
    ImGui::SetNextWindowPos(ImVec2(0, windowHeight - height), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(windowWidth, height), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("##plots", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings);
    const std::size_t n = std::max<std::size_t>(views.views().size(), 1);
    const float column = (windowWidth - 20.0f) / static_cast<float>(n);
    for (std::size_t i = 0; i < views.views().size(); ++i) {
        const View& v = views.views()[i];
        if (i > 0) ImGui::SameLine(10.0f + column * static_cast<float>(i));
        ImGui::BeginGroup();
        std::vector<float> ms, energy;
        for (const HistorySample& s : v.history) {
            ms.push_back(s.stepMs);
            energy.push_back(s.energy);
        }
        const float width = column - 20.0f;
        char overlay[96];
        std::snprintf(overlay, sizeof overlay, "%s step %.3f ms", v.backend.c_str(), v.lastStepMs);
        ImGui::PlotLines(("##ms" + std::to_string(i)).c_str(), ms.data(), static_cast<int>(ms.size()), 0, overlay, 0.0f,
                         FLT_MAX, ImVec2(width, 60));
        std::snprintf(overlay, sizeof overlay, "energy %.4g J", v.energy);
        ImGui::PlotLines(("##energy" + std::to_string(i)).c_str(), energy.data(), static_cast<int>(energy.size()), 0,
                         overlay, FLT_MAX, FLT_MAX, ImVec2(width, 60));
        ImGui::EndGroup();
    }
    ImGui::End();
}

}  // namespace anyphys::testbed
