// glTF's metallic-roughness materials on Prism's Phong model, by one rule (docs/scene-format.md,
// "glTF"). With F0 = mix(0.04, base, metallic), α = roughness², n = clamp((2/α² − 2)/4, 1, 4096):
//   diffuse       = base × (1 − metallic) × (1 − transmission)   (base colour texture: diffuseMap)
//   ambient       = diffuse
//   specular      = F0 × (n + 2)/(2π)      (a normalised Phong lobe with the Blinn-Phong
//   shininess     = n                       exponent's width; Phong's lobe is 4× narrower)
//   reflectance   = metallic × base        (a tinted mirror)
//   transmittance = transmission × base × (1 − metallic), ior from KHR_materials_ior, Fresnel on
// Everything else a material holds (emissive, normal, occlusion and metallic-roughness textures,
// alpha, other extensions) is named in a warning.
#pragma once

#include <cstdint>
#include <vector>

#include "parse/GltfDocument.h"
#include "scene/SceneDescription.h"

namespace prism {

// The model's material for each of the document's materials, in order. Images are decoded once
// each, appended to textures (the materials' diffuseMap indices point there).
std::vector<MaterialDesc> readGltfMaterials(GltfDocument& doc, std::vector<TextureDesc>& textures);

// The material a primitive without one gets: Prism's default grey (glTF's own default, a white
// metal, would make every such mesh a mirror).
MaterialDesc defaultGltfMaterial(const std::string& file);

// KHR_texture_transform (uv' = offset + R(rotation)·(scale ⊙ uv), with glTF's v down) as
// Prism's TextureMap on coordinates whose v was flipped (v_prism = 1 − v_gltf).
TextureMap gltfTextureTransform(Vec2 offset, float rotation, Vec2 scale);

}  // namespace prism
