#include "parse/GltfScene.h"

#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace prism {

namespace {

glm::mat4 localTransform(const GltfJson& node) {
  if (const std::optional<GltfJson> matrix = node.member("matrix")) {
    const std::vector<double> m = node.numbersOr("matrix", 16, {});
    glm::mat4 out;
    for (int i = 0; i < 16; ++i) glm::value_ptr(out)[i] = static_cast<float>(m[i]);  // column-major
    return out;
  }
  const std::vector<double> t = node.numbersOr("translation", 3, {0, 0, 0});
  const std::vector<double> r = node.numbersOr("rotation", 4, {0, 0, 0, 1});
  const std::vector<double> s = node.numbersOr("scale", 3, {1, 1, 1});
  glm::quat q(static_cast<float>(r[3]), static_cast<float>(r[0]), static_cast<float>(r[1]),
              static_cast<float>(r[2]));
  const float length = glm::length(q);
  if (!(length > 0.0f)) node.required("rotation").fail("the rotation quaternion has length 0");
  q /= length;
  const glm::mat4 translation = glm::translate(glm::mat4(1.0f), glm::vec3(t[0], t[1], t[2]));
  const glm::mat4 scale = glm::scale(glm::mat4(1.0f), glm::vec3(s[0], s[1], s[2]));
  return translation * glm::mat4_cast(q) * scale;
}

// The scene's root nodes, each with the JSON value that names it: `scene`, else scenes[0], else
// every node that is nobody's child.
std::vector<std::pair<uint64_t, GltfJson>> rootNodes(const GltfDocument& doc,
                                                     const std::vector<bool>& hasParent) {
  std::vector<std::pair<uint64_t, GltfJson>> roots;
  const std::vector<GltfJson> scenes = doc.root.objectsOf("scenes");
  if (!scenes.empty()) {
    const std::optional<GltfJson> chosen = doc.root.member("scene");
    const uint64_t s = chosen ? chosen->index() : 0;
    const GltfJson& scene = doc.at(scenes, s, chosen ? *chosen : doc.root, "scenes");
    if (const std::optional<GltfJson> nodes = scene.member("nodes")) {
      for (const GltfJson& node : nodes->items()) roots.emplace_back(node.index(), node);
    }
    return roots;
  }
  for (size_t i = 0; i < doc.nodes.size(); ++i) {
    if (!hasParent[i]) roots.emplace_back(i, doc.nodes[i]);
  }
  return roots;
}

// Every node's parent is unique: a node listed as the child of two, or of itself, is refused
// (a cycle without a root is caught by the walk, which meets a node it has seen).
std::vector<bool> checkParents(const GltfDocument& doc) {
  std::vector<int64_t> parent(doc.nodes.size(), -1);
  for (size_t p = 0; p < doc.nodes.size(); ++p) {
    const std::optional<GltfJson> children = doc.nodes[p].member("children");
    if (!children) continue;
    for (const GltfJson& child : children->items()) {
      const uint64_t c = child.index();
      doc.at(doc.nodes, c, child, "nodes");
      if (c == p) child.fail("nodes[" + std::to_string(c) + "] lists itself as a child (a cycle)");
      if (parent[c] >= 0) {
        child.fail("nodes[" + std::to_string(c) + "] is already a child of nodes[" +
                   std::to_string(parent[c]) + "] (glTF nodes form trees, without shared nodes)");
      }
      parent[c] = static_cast<int64_t>(p);
    }
  }
  std::vector<bool> hasParent(doc.nodes.size());
  for (size_t i = 0; i < parent.size(); ++i) hasParent[i] = parent[i] >= 0;
  return hasParent;
}

CameraDesc cameraOf(const GltfDocument& doc, const GltfJson& ref, const glm::mat4& world) {
  const GltfJson& camera = doc.at(doc.cameras, ref.index(), ref, "cameras");
  CameraDesc c;
  c.loc = FileLoc{doc.file, 0, 0};
  const glm::vec3 position(world[3]);
  const glm::vec3 forward = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
  const glm::vec3 up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
  if (!isFinite(forward) || !isFinite(up) || !isFinite(position)) {
    ref.fail("the node's transform gives the camera no direction");
  }
  c.position = position;
  c.lookAt = position + forward;
  c.up = up;
  const std::string_view type = camera.required("type").string();
  if (type == "perspective") {
    const GltfJson p = camera.required("perspective");
    const double yfov = p.required("yfov").number();
    if (!(yfov > 0.0 && yfov < std::numbers::pi)) p.required("yfov").fail("must lie in (0, π)");
    c.fovDegrees = static_cast<float>(yfov * 180.0 / std::numbers::pi);
    c.nearClip = static_cast<float>(std::max(0.0, p.numberOr("znear", 0.0)));
  } else if (type == "orthographic") {
    const GltfJson o = camera.required("orthographic");
    const double xmag = o.required("xmag").number();
    if (!(xmag != 0.0)) o.required("xmag").fail("must not be 0");
    c.projection = Projection::Orthographic;
    c.width = static_cast<float>(2.0 * std::abs(xmag));  // xmag is half the view's width
  } else {
    camera.required("type").fail("unknown camera type '" + std::string(type) + "'");
  }
  return c;
}

void addLight(GltfDocument& doc, const GltfJson& ref, const glm::mat4& world,
              std::vector<PointLightDesc>& lights) {
  const GltfJson& light = doc.at(doc.lights, ref.index(), ref, "KHR_lights_punctual.lights");
  const std::string_view type = light.required("type").string();
  if (type == "directional") {
    doc.warn("directional light", light.path() +
                                      ": directional lights are not modelled: skipped (only "
                                      "point and spot lights are read)");
    return;
  }
  if (type == "spot") {
    doc.warn("spot light", light.path() +
                               ": a spot light's cone is not modelled: it shines as a point "
                               "light of the same intensity in every direction");
  } else if (type != "point") {
    light.required("type").fail("unknown light type '" + std::string(type) + "'");
  }
  if (light.member("range")) {
    doc.warn("light range", light.path() +
                                ".range: not modelled: the light falls off with the "
                                "inverse square of distance without a cut-off");
  }
  const std::vector<double> color = light.numbersOr("color", 3, {1, 1, 1});
  const float candela = static_cast<float>(light.numberOr("intensity", 1.0));
  PointLightDesc p;
  p.position = glm::vec3(world[3]);
  p.intensity = Color(color[0], color[1], color[2]) * (candela / kLumensPerWatt);
  p.loc = FileLoc{doc.file, 0, 0};
  lights.push_back(p);
}

void visitNode(GltfDocument& doc, const GltfJson& node, const glm::mat4& world,
               GltfSceneContents& out) {
  if (const std::optional<uint64_t> mesh = node.optionalIndex("mesh")) {
    doc.at(doc.meshes, *mesh, *node.member("mesh"), "meshes");
    out.meshes.push_back({*mesh, world, node.path()});
  }
  if (node.member("skin") || node.member("weights")) {
    doc.warn("skin", node.path() +
                         ": skins and morph weights are not modelled: the rest pose "
                         "is rendered");
  }
  if (const std::optional<GltfJson> camera = node.member("camera")) {
    if (!out.camera) {
      out.camera = cameraOf(doc, *camera, world);
    } else {
      doc.warn("more cameras", node.path() +
                                   ": a further camera is skipped (the first in the "
                                   "scene's order is used)");
    }
  }
  const std::optional<GltfJson> ext = node.member("extensions");
  if (const std::optional<GltfJson> punctual =
          ext ? ext->member("KHR_lights_punctual") : std::nullopt) {
    addLight(doc, punctual->required("light"), world, out.lights);
  }
}

}  // namespace

GltfSceneContents walkGltfScene(GltfDocument& doc) {
  const std::vector<bool> hasParent = checkParents(doc);
  std::vector<bool> seen(doc.nodes.size());
  GltfSceneContents out;
  struct Pending {
    uint64_t node;
    glm::mat4 parentWorld;
    GltfJson from;
  };
  std::vector<Pending> stack;  // explicit, so a deep hierarchy cannot overflow the call stack
  const std::vector<std::pair<uint64_t, GltfJson>> roots = rootNodes(doc, hasParent);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
    stack.push_back({it->first, glm::mat4(1.0f), it->second});
  }
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    const GltfJson& node = doc.at(doc.nodes, p.node, p.from, "nodes");
    if (seen[p.node]) {
      p.from.fail("nodes[" + std::to_string(p.node) +
                  "] is reached twice: the node graph has a "
                  "cycle or lists a node twice");
    }
    seen[p.node] = true;
    const glm::mat4 world = p.parentWorld * localTransform(node);
    for (int c = 0; c < 4; ++c) {
      if (!isFinite(glm::vec3(world[c])) || !std::isfinite(world[c][3])) {
        node.fail("the world transform is not finite");
      }
    }
    visitNode(doc, node, world, out);
    if (const std::optional<GltfJson> children = node.member("children")) {
      const std::vector<GltfJson> items = children->items();
      for (auto it = items.rbegin(); it != items.rend(); ++it)
        stack.push_back({it->index(), world, *it});
    }
  }
  return out;
}

}  // namespace prism
