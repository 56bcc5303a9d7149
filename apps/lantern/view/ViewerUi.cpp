// The viewer's ImGui panel and help overlay, drawn in the WindowTarget's overlay pass.
#include "view/ViewerUi.h"

#include <algorithm>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <cmath>
#include <imgui.h>
#include <string>

namespace lantern::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

VkResult g_imguiVkError = VK_SUCCESS;
void checkImguiVk(VkResult r) {
    if (r < 0) g_imguiVkError = r;
}

// Edits a linear RGB colour stored in doubles; true when changed.
bool colour3(const char* label, glm::dvec3& c) {
    float f[3] = {float(c.x), float(c.y), float(c.z)};
    if (!ImGui::ColorEdit3(label, f, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR))
        return false;
    for (int i = 0; i < 3; ++i)
        c[i] = std::max(0.0, double(std::isfinite(f[i]) ? f[i] : 0.0f));
    return true;
}

bool colour4(const char* label, glm::dvec4& c) {
    float f[4] = {float(c.x), float(c.y), float(c.z), float(c.w)};
    if (!ImGui::ColorEdit4(label, f, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR))
        return false;
    for (int i = 0; i < 4; ++i)
        c[i] = std::max(0.0, double(std::isfinite(f[i]) ? f[i] : 0.0f));
    c.w = std::min(c.w, 1.0);
    return true;
}

bool dragDouble(const char* label, double& v, double speed, double lo, double hi,
                const char* format = "%.4g") {
    return ImGui::DragScalar(label, ImGuiDataType_Double, &v, float(speed), &lo, &hi, format,
                             ImGuiSliderFlags_AlwaysClamp);
}

bool editSide(MaterialSide& side) {
    bool changed = false;
    changed |= colour3("ambient", side.ambient);
    changed |= colour4("diffuse", side.diffuse);
    changed |= colour3("specular", side.specular);
    changed |= colour3("emission", side.emission);
    changed |= dragDouble("shininess", side.shininess, 0.5, 0.0, 1e4);
    return changed;
}

// The node that places light `index` (the first in the file), or -1.
int lightNode(const Scene& scene, int index) {
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (scene.nodes[i].light == index) return int(i);
    return -1;
}

// GL's falloff: constant, linear and quadratic attenuation; a spot's exponent and cutoff.
bool editGlFalloff(Light& l) {
    bool changed = false;
    double k[3] = {l.attenuation.x, l.attenuation.y, l.attenuation.z};
    const double lo = 0.0, hi = 1e6;
    if (ImGui::DragScalarN("kc kl kq", ImGuiDataType_Double, k, 3, 0.01f, &lo, &hi, "%.4g",
                           ImGuiSliderFlags_AlwaysClamp)) {
        // GL refuses all three zero (the scene format too): keep kc at least tiny then.
        if (k[0] == 0.0 && k[1] == 0.0 && k[2] == 0.0) k[0] = 1e-6;
        l.attenuation = {k[0], k[1], k[2]};
        changed = true;
    }
    if (l.type == LightType::Spot) {
        changed |= dragDouble("spot exponent", l.spotExponent, 0.2, 0.0, 1e4);
        bool cone = l.spotCutoffDeg != 180.0;
        if (ImGui::Checkbox("cone", &cone)) {
            l.spotCutoffDeg = cone ? 45.0 : 180.0;
            changed = true;
        }
        if (cone) changed |= dragDouble("cutoff (deg)", l.spotCutoffDeg, 0.2, 0.0, 90.0);
    }
    return changed;
}

// glTF's falloff: a range (or none), a spot's outer and inner cone.
bool editGltfFalloff(Light& l) {
    bool changed = false;
    bool limited = !std::isinf(l.range);
    if (ImGui::Checkbox("limited range", &limited)) {
        l.range = limited ? 10.0 : kInfinity;
        changed = true;
    }
    if (limited) changed |= dragDouble("range", l.range, 0.05, 1e-6, 1e12);
    if (l.type == LightType::Spot) {
        double outer = l.outerConeAngle * 180.0 / kPi, inner = l.innerConeAngle * 180.0 / kPi;
        if (dragDouble("outer cone (deg)", outer, 0.2, 0.01, 90.0)) {
            l.outerConeAngle = outer * kPi / 180.0;
            l.innerConeAngle = std::min(l.innerConeAngle, l.outerConeAngle * 0.999);
            changed = true;
        }
        if (dragDouble("inner cone (deg)", inner, 0.2, 0.0, outer * 0.999)) {
            l.innerConeAngle = std::min(inner * kPi / 180.0, l.outerConeAngle * 0.999);
            changed = true;
        }
    }
    return changed;
}

// The position of the node that places light `index` (its direction stays the node's).
bool editLightPosition(Scene& scene, int index) {
    const int node = lightNode(scene, index);
    if (node < 0) {
        ImGui::TextDisabled("(no node places this light)");
        return false;
    }
    bool changed = false;
    Node& n = scene.nodes[std::size_t(node)];
    glm::dvec3 p = n.matrix ? glm::dvec3((*n.matrix)[3]) : n.translation;
    double v[3] = {p.x, p.y, p.z};
    const double lo = -1e12, hi = 1e12;
    if (ImGui::DragScalarN("position", ImGuiDataType_Double, v, 3, 0.05f, &lo, &hi, "%.4g",
                           ImGuiSliderFlags_AlwaysClamp)) {
        if (n.matrix)
            (*n.matrix)[3] = glm::dvec4(v[0], v[1], v[2], 1.0);
        else
            n.translation = {v[0], v[1], v[2]};
        changed = true;
    }
    if (scene.lights[std::size_t(index)].type != LightType::Point)
        ImGui::TextDisabled("direction: the node's -Z (rotate the node in the file)");
    return changed;
}

bool editLight(Scene& scene, int index) {
    Light& l = scene.lights[std::size_t(index)];
    bool changed = ImGui::Checkbox("casts shadows", &l.castShadows);
    int type = int(l.type);
    const char* types[] = {"directional", "point", "spot"};
    if (ImGui::Combo("type", &type, types, 3)) {
        l.type = LightType(type);
        changed = true;
    }
    changed |= colour3("ambient", l.ambient);
    changed |= colour3("diffuse", l.diffuse);
    changed |= colour3("specular", l.specular);
    int falloff = int(l.falloff);
    const char* falloffs[] = {"GL (attenuation, cutoff)", "glTF (range, cone)"};
    if (ImGui::Combo("falloff", &falloff, falloffs, 2)) {
        l.falloff = LightFalloff(falloff);
        changed = true;
    }
    changed |= l.falloff == LightFalloff::Gl ? editGlFalloff(l) : editGltfFalloff(l);
    changed |= editLightPosition(scene, index);
    return changed;
}

} // namespace

Result<std::unique_ptr<ViewerUi>> ViewerUi::create(GLFWwindow* window, WindowTarget& target) {
    std::unique_ptr<ViewerUi> ui(new ViewerUi());
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini left in the working folder
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.95f;
    if (!ImGui_ImplGlfw_InitForVulkan(window, true))
        return makeError(ErrorCode::Internal, "ImGui's GLFW backend failed to initialise");
    ui->m_glfw = true;
    const OverlayContext& oc = target.overlayContext();
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = oc.instance;
    info.PhysicalDevice = oc.physicalDevice;
    info.Device = oc.device;
    info.QueueFamily = oc.queueFamily;
    info.Queue = oc.queue;
    info.PipelineCache = oc.pipelineCache;
    info.DescriptorPool = oc.descriptorPool;
    info.Subpass = 0;
    info.MinImageCount = oc.imageCount;
    info.ImageCount = oc.imageCount;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkImguiVk;
    if (!ImGui_ImplVulkan_Init(&info, oc.renderPass))
        return makeError(ErrorCode::Internal, "ImGui's Vulkan backend failed to initialise");
    ui->m_vulkan = true;
    LANTERN_TRY(
        target.submitOnce([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); }));
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    if (g_imguiVkError != VK_SUCCESS)
        return makeError(ErrorCode::Internal, "ImGui's Vulkan backend failed (VkResult " +
                                                  std::to_string(int(g_imguiVkError)) + ")");
    return ui;
}

ViewerUi::~ViewerUi() {
    if (m_vulkan) ImGui_ImplVulkan_Shutdown();
    if (m_glfw) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

bool ViewerUi::wantsMouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}
bool ViewerUi::wantsKeyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

OverlayRecorder ViewerUi::recorder() const {
    return [](VkCommandBuffer cmd) {
        if (ImDrawData* d = ImGui::GetDrawData(); d && d->CmdListsCount > 0)
            ImGui_ImplVulkan_RenderDrawData(d, cmd);
    };
}

namespace {

// F1: the keys, as docs/viewer.md lists them.
void helpWindow(ViewerState& st) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.8f);
    ImGui::Begin("Keys", &st.showHelp,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoSavedSettings);
    if (ImGui::BeginTable("keys", 2)) {
        for (const KeyHelp& k : viewerKeys()) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(k.keys);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(k.action);
        }
        ImGui::EndTable();
    }
    ImGui::End();
}

// The panel's sections, top to bottom.

void playbackSection(ViewerState& st) {
    if (!ImGui::CollapsingHeader("Playback", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Checkbox("playing", &st.playing);
    ImGui::SameLine();
    const double lo = 0.0, hi = 16.0;
    ImGui::SetNextItemWidth(100);
    ImGui::DragScalar("speed", ImGuiDataType_Double, &st.speed, 0.01f, &lo, &hi, "%.2fx");
    double t0 = st.startTime(), t1 = std::max(st.endTime(), st.startTime() + 1e-9);
    ImGui::SliderScalar("time", ImGuiDataType_Double, &st.time, &t0, &t1, "%.3f s");
    std::string current = st.animation < 0 ? "all" : st.animations[std::size_t(st.animation)].name;
    if (!ImGui::BeginCombo("animation", current.c_str())) return;
    if (ImGui::Selectable("all", st.animation < 0)) {
        st.animation = -1;
        st.applyAnimationChoice();
    }
    for (std::size_t i = 0; i < st.animations.size(); ++i) {
        const std::string name = std::to_string(i) + ": " + st.animations[i].name;
        if (ImGui::Selectable(name.c_str(), st.animation == int(i))) {
            st.animation = int(i);
            st.applyAnimationChoice();
        }
    }
    ImGui::EndCombo();
}

void cameraSection(ViewerState& st) {
    if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const Scene& scene = *st.scene;
    std::string current = st.camera.isFree() ? "free (orbit / fly)"
                          : st.sceneCamera < 0
                              ? "scene default"
                              : std::to_string(st.sceneCamera) + ": " +
                                    scene.cameras[std::size_t(st.sceneCamera)].name;
    if (ImGui::BeginCombo("camera", current.c_str())) {
        if (ImGui::Selectable("scene default", !st.camera.isFree() && st.sceneCamera < 0)) {
            st.sceneCamera = -1;
            st.cameraPicked = true;
        }
        for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
            const std::string name = std::to_string(i) + ": " + scene.cameras[i].name;
            if (ImGui::Selectable(name.c_str(), !st.camera.isFree() && st.sceneCamera == int(i))) {
                st.sceneCamera = int(i);
                st.cameraPicked = true;
            }
        }
        ImGui::EndCombo();
    }
    if (ImGui::Button("frame all")) st.frameAllRequested = true;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::BeginCombo("##view", "view from")) {
        for (ViewDirection v : kViewDirections)
            if (ImGui::Selectable(toString(v))) st.viewRequested = v;
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    ImGui::Checkbox("fly", &st.fly);
    ImGui::SameLine();
    ImGui::Checkbox("headlight", &st.headlight);
    ImGui::Checkbox("quad view", &st.quad);
}

void shadingSection(ViewerState& st) {
    if (!ImGui::CollapsingHeader("Shading", ImGuiTreeNodeFlags_DefaultOpen)) return;
    RenderOptions& o = st.options;
    // The viewer starts with the scene's lighting model resolved into the options.
    int shading = int(o.shading.value_or(ShadingMode::Phong));
    bool pressed = ImGui::RadioButton("flat", &shading, int(ShadingMode::Flat));
    ImGui::SameLine();
    pressed |= ImGui::RadioButton("gouraud", &shading, int(ShadingMode::Gouraud));
    ImGui::SameLine();
    pressed |= ImGui::RadioButton("phong", &shading, int(ShadingMode::Phong));
    if (pressed) o.shading = ShadingMode(shading);
    int specular = int(o.specular.value_or(SpecularModel::Blinn));
    pressed = ImGui::RadioButton("blinn", &specular, int(SpecularModel::Blinn));
    ImGui::SameLine();
    pressed |= ImGui::RadioButton("phong specular", &specular, int(SpecularModel::Phong));
    if (pressed) o.specular = SpecularModel(specular);
    bool local = o.localViewer.value_or(false), twoSided = o.twoSided.value_or(false);
    if (ImGui::Checkbox("local viewer", &local)) o.localViewer = local;
    ImGui::SameLine();
    if (ImGui::Checkbox("two-sided", &twoSided)) o.twoSided = twoSided;
    ImGui::Checkbox("wireframe", &o.wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("normals", &o.normals);
    // Shadows: every light (as --shadows), or each light's own switch under Lights.
    ImGui::Checkbox("shadows (every light)", &o.shadows.all);
    int filter = int(o.shadows.filter);
    pressed = ImGui::RadioButton("hardware", &filter, int(ShadowFilter::Hardware));
    ImGui::SameLine();
    pressed |= ImGui::RadioButton("pcf", &filter, int(ShadowFilter::Pcf));
    ImGui::SameLine();
    pressed |= ImGui::RadioButton("pcss", &filter, int(ShadowFilter::Pcss));
    if (pressed) o.shadows.filter = ShadowFilter(filter);
    ImGui::SliderInt("shadow kernel", &o.shadows.kernel, 1, 9);
    o.shadows.kernel |= 1;  // odd
    ImGui::SliderInt("cascades", &o.shadows.cascades, 1, kMaxShadowCascades);
    if (o.shadows.filter == ShadowFilter::Pcss) {
        float radius = float(o.shadows.lightRadius), sun = float(o.shadows.sunRadius);
        if (ImGui::DragFloat("light radius", &radius, 0.005f, 0.0f, 1e6f)) o.shadows.lightRadius = radius;
        if (ImGui::SliderFloat("sun radius (deg)", &sun, 0.0f, 10.0f)) o.shadows.sunRadius = sun;
    }
    // Transparency (--transparency): how blended materials are composited.
    int transparency = int(
        o.transparency.value_or(o.glCompat ? TransparencyMethod::Sorted : TransparencyMethod::Exact));
    pressed = ImGui::RadioButton("sorted", &transparency, int(TransparencyMethod::Sorted));
    ImGui::SameLine();
    pressed |= ImGui::RadioButton("exact", &transparency, int(TransparencyMethod::Exact));
    ImGui::SameLine();
    pressed |= ImGui::RadioButton("weighted", &transparency, int(TransparencyMethod::Weighted));
    if (pressed) o.transparency = TransparencyMethod(transparency);
}

void lightsSection(ViewerState& st) {
    if (!ImGui::CollapsingHeader("Lights")) return;
    Scene& scene = *st.scene;
    if (scene.lights.empty()) ImGui::TextDisabled("none: GL's default light 0 (a headlight)");
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        ImGui::PushID(int(i));
        const std::string name = std::to_string(i) + ": " + scene.lights[i].name;
        if (ImGui::TreeNode(name.c_str())) {
            st.edited |= editLight(scene, int(i));
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
}

void materialsSection(ViewerState& st) {
    if (!ImGui::CollapsingHeader("Materials")) return;
    Scene& scene = *st.scene;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        ImGui::PushID(1000 + int(i));
        Material& m = scene.materials[i];
        const std::string name = std::to_string(i) + ": " + m.name;
        if (ImGui::TreeNode(name.c_str())) {
            if (m.back) ImGui::TextDisabled("front");
            st.edited |= editSide(m.front);
            if (m.back) {
                ImGui::TextDisabled("back");
                ImGui::PushID("back");
                st.edited |= editSide(*m.back);
                ImGui::PopID();
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
}

// F2: the side panel along the window's right edge.
void panel(ViewerState& st, const std::string& status) {
    const ImGuiIO& io = ImGui::GetIO();
    const float width = std::min(340.0f, io.DisplaySize.x * 0.45f);
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - width, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y), ImGuiCond_Always);
    ImGui::Begin("Lantern", &st.showPanel,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse);
    ImGui::TextWrapped("%s", st.source.c_str());
    ImGui::TextDisabled("%s", status.c_str());
    playbackSection(st);
    cameraSection(st);
    shadingSection(st);
    lightsSection(st);
    materialsSection(st);
    if (ImGui::Button("screenshot (F12)")) st.screenshotRequested = true;
    ImGui::End();
}

} // namespace

void ViewerUi::build(ViewerState& st, const std::string& status) {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (st.showHelp) helpWindow(st);
    if (st.showPanel) panel(st, status);
    ImGui::Render();
}

} // namespace lantern::cli
