#include "parse/GltfMaterial.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "parse/GltfUri.h"
#include "parse/TextureFile.h"

namespace prism {

namespace {

constexpr float kDielectricF0 = 0.04f;
constexpr float kMaxShininess = 4096.0f;

Color colorOf(const std::vector<double>& v) {
  return Color(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}

// The encoded bytes of images[i]: a data URI (decoded into keep), a file beside the glTF, or a
// buffer view.
std::span<const uint8_t> imageBytes(GltfDocument& doc, const GltfJson& image, std::string& name,
                                    std::vector<uint8_t>& keep) {
  if (const std::optional<GltfJson> uriJson = image.member("uri")) {
    const std::string_view uri = uriJson->string();
    try {
      if (const std::optional<DataUri> data = splitDataUri(uri)) {
        doc.charge(base64DecodedSize(data->payload), image.path() + "'s data URI");
        keep = decodeBase64(data->payload);
        name = doc.file + "#" + image.path();
        return keep;
      }
      name = uriToRelativePath(uri);
    } catch (const std::invalid_argument& e) {
      uriJson->fail(e.what());
    }
    const std::optional<std::string_view> bytes = doc.readFile(name);
    if (!bytes) uriJson->fail("the image file '" + name + "' is missing");
    return {reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()};
  }
  const GltfJson view = image.required("bufferView");
  const GltfJson& bufferView = doc.at(doc.bufferViews, view.index(), view, "bufferViews");
  const uint64_t b = bufferView.required("buffer").index();
  doc.at(doc.buffers, b, bufferView.required("buffer"), "buffers");
  const uint64_t offset = bufferView.indexOr("byteOffset", 0);
  const uint64_t length = bufferView.required("byteLength").index();
  const std::span<const uint8_t> buffer = doc.bufferBytes[b];
  if (offset > buffer.size() || length > buffer.size() - offset) {
    bufferView.fail("lies past the end of buffers[" + std::to_string(b) + "]");
  }
  name = doc.file + "#" + image.path();
  return buffer.subspan(offset, length);
}

class TextureReader {
 public:
  TextureReader(GltfDocument& doc, std::vector<TextureDesc>& textures)
      : doc_(doc), textures_(textures) {}

  // The model's texture index for a textureInfo's texture, or nothing (with a warning) when its
  // image cannot be used.
  std::optional<uint32_t> textureOf(const GltfJson& info) {
    const GltfJson index = info.required("index");
    const GltfJson& texture = doc_.at(doc_.textures, index.index(), index, "textures");
    const std::optional<uint64_t> source = texture.optionalIndex("source");
    if (!source) {
      doc_.warn("texture source", texture.path() +
                                      ": no PNG or JPEG source (only an extension's image "
                                      "format): the material's colour is used without it");
      return std::nullopt;
    }
    if (const std::optional<uint64_t> sampler = texture.optionalIndex("sampler")) {
      checkSampler(doc_.root.objectsOf("samplers"), *sampler, texture);
    }
    const auto found = loaded_.find(*source);
    if (found != loaded_.end()) return found->second;
    const GltfJson& image = doc_.at(doc_.images, *source, *texture.member("source"), "images");
    std::string name;
    std::vector<uint8_t> keep;
    const std::span<const uint8_t> bytes = imageBytes(doc_, image, name, keep);
    if (!name.starts_with(doc_.file + "#")) name = pathBeside(name);
    textures_.push_back(
        decodeTexture(bytes, name, FileLoc{doc_.file + ": " + image.path(), 0, 0}, doc_.limit));
    const auto id = static_cast<uint32_t>(textures_.size() - 1);
    loaded_.emplace(*source, id);
    return id;
  }

 private:
  std::string pathBeside(const std::string& relative) const {
    const size_t slash = doc_.file.find_last_of('/');
    return slash == std::string::npos ? relative : doc_.file.substr(0, slash + 1) + relative;
  }

  void checkSampler(const std::vector<GltfJson>& samplers, uint64_t i, const GltfJson& texture) {
    const GltfJson& sampler = doc_.at(samplers, i, *texture.member("sampler"), "samplers");
    constexpr uint64_t kRepeat = 10497;
    if (sampler.indexOr("wrapS", kRepeat) != kRepeat ||
        sampler.indexOr("wrapT", kRepeat) != kRepeat) {
      doc_.warn("sampler wrap", sampler.path() +
                                    ": clamped and mirrored wrapping are not modelled: textures "
                                    "repeat");
    }
  }

  GltfDocument& doc_;
  std::vector<TextureDesc>& textures_;
  std::map<uint64_t, uint32_t> loaded_;  // glTF image → model texture
};

void warnUnmodelled(GltfDocument& doc, const GltfJson& material) {
  for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) {
    if (material.member(key)) {
      doc.warn(key, material.path() + "." + key + ": not modelled, ignored");
    }
  }
  const std::vector<double> emissive = material.numbersOr("emissiveFactor", 3, {0, 0, 0});
  if (emissive[0] > 0 || emissive[1] > 0 || emissive[2] > 0) {
    doc.warn("emissive", material.path() +
                             ".emissiveFactor: emission is not modelled: the "
                             "surface does not glow");
  }
  const std::string_view alpha = material.stringOr("alphaMode", "OPAQUE");
  if (alpha != "OPAQUE") {
    doc.warn("alphaMode", material.path() + ".alphaMode " + std::string(alpha) +
                              ": transparency by alpha is not modelled: the surface is opaque");
  }
  if (const std::optional<GltfJson> ext = material.member("extensions")) {
    for (const std::string_view name : ext->keys()) {
      if (name == "KHR_materials_transmission" || name == "KHR_materials_ior") continue;
      doc.warn("material " + std::string(name),
               material.path() + ".extensions." + std::string(name) + ": not modelled, ignored");
    }
  }
}

TextureMap textureMapOf(const GltfJson& info, uint32_t texture, GltfDocument& doc) {
  if (info.indexOr("texCoord", 0) != 0) {
    doc.warn("texCoord", info.path() + ".texCoord: only TEXCOORD_0 is read: it is used instead");
  }
  const std::optional<GltfJson> ext = info.member("extensions");
  const std::optional<GltfJson> transform =
      ext ? ext->member("KHR_texture_transform") : std::nullopt;
  TextureMap map;
  if (transform && transform->indexOr("texCoord", 0) != 0) {
    doc.warn("texCoord",
             transform->path() + ".texCoord: only TEXCOORD_0 is read: it is used instead");
  }
  if (transform) {
    const std::vector<double> offset = transform->numbersOr("offset", 2, {0, 0});
    const std::vector<double> scale = transform->numbersOr("scale", 2, {1, 1});
    map = gltfTextureTransform(Vec2(offset[0], offset[1]),
                               static_cast<float>(transform->numberOr("rotation", 0.0)),
                               Vec2(scale[0], scale[1]));
  } else {
    map = gltfTextureTransform(Vec2(0.0f), 0.0f, Vec2(1.0f));
  }
  map.texture = texture;
  return map;
}

MaterialDesc readMaterial(GltfDocument& doc, const GltfJson& material, TextureReader& textures) {
  MaterialDesc m;
  m.name = std::string(material.stringOr("name", material.path()));
  m.loc = FileLoc{doc.file, 0, 0};
  const std::optional<GltfJson> pbr = material.member("pbrMetallicRoughness");
  std::vector<double> baseFactor{1, 1, 1, 1};
  double metallic = 1.0, roughness = 1.0;
  if (pbr) {
    baseFactor = pbr->numbersOr("baseColorFactor", 4, baseFactor);
    metallic = std::clamp(pbr->numberOr("metallicFactor", 1.0), 0.0, 1.0);
    roughness = std::clamp(pbr->numberOr("roughnessFactor", 1.0), 0.0, 1.0);
    if (const std::optional<GltfJson> info = pbr->member("baseColorTexture")) {
      if (const std::optional<uint32_t> t = textures.textureOf(*info)) {
        m.diffuseMap = textureMapOf(*info, *t, doc);
      }
    }
    if (pbr->member("metallicRoughnessTexture")) {
      doc.warn("metallicRoughnessTexture", pbr->path() +
                                               ".metallicRoughnessTexture: not modelled: the "
                                               "factors are used alone");
    }
  }
  const Color base = glm::clamp(colorOf(baseFactor), Color(0.0f), Color(1.0f));
  double transmission = 0.0;
  float ior = 1.5f;
  if (const std::optional<GltfJson> ext = material.member("extensions")) {
    if (const std::optional<GltfJson> t = ext->member("KHR_materials_transmission")) {
      transmission = std::clamp(t->numberOr("transmissionFactor", 0.0), 0.0, 1.0);
      if (t->member("transmissionTexture")) {
        doc.warn("transmissionTexture", t->path() +
                                            ".transmissionTexture: not modelled: the "
                                            "factor is used alone");
      }
    }
    if (const std::optional<GltfJson> i = ext->member("KHR_materials_ior")) {
      ior = static_cast<float>(i->numberOr("ior", 1.5));
      if (ior < 1.0f) ior = 1.0f;  // glTF allows 0 (meaning "no refraction"); Prism needs ≥ 1
    }
  }
  const float mt = static_cast<float>(metallic);
  const float alpha = std::max(static_cast<float>(roughness * roughness), 1e-3f);
  const float shininess = std::clamp((2.0f / (alpha * alpha) - 2.0f) / 4.0f, 1.0f, kMaxShininess);
  const Color f0 = glm::mix(Color(kDielectricF0), base, mt);
  m.diffuse = base * (1.0f - mt) * (1.0f - static_cast<float>(transmission));
  m.ambient = m.diffuse;
  m.shininess = shininess;
  m.specular = f0 * ((shininess + 2.0f) / (2.0f * std::numbers::pi_v<float>));
  m.reflectance = base * mt;
  m.transmittance = base * (1.0f - mt) * static_cast<float>(transmission);
  m.ior = ior;
  m.fresnel = true;
  warnUnmodelled(doc, material);
  return m;
}

}  // namespace

TextureMap gltfTextureTransform(Vec2 offset, float rotation, Vec2 scale) {
  // glTF samples (u, v_g) with v_g down; Prism samples (u, 1 − v_g). With D = diag(1, −1) and
  // e = (0, 1): uv'_p = D·(o + R(θ)·S·(D·uv_p + e)) + e = R(−θ)·S·uv_p + D·o + D·R(θ)·S·e + e.
  TextureMap map;
  map.scale = scale;
  map.rotation = -rotation;
  const float s = std::sin(rotation), c = std::cos(rotation);
  map.offset = Vec2(offset.x - scale.y * s, 1.0f - offset.y - scale.y * c);
  return map;
}

MaterialDesc defaultGltfMaterial(const std::string& file) {
  MaterialDesc m;
  m.name = "glTF default";
  m.loc = FileLoc{file, 0, 0};
  return m;
}

std::vector<MaterialDesc> readGltfMaterials(GltfDocument& doc, std::vector<TextureDesc>& textures) {
  TextureReader reader(doc, textures);
  std::vector<MaterialDesc> out;
  out.reserve(doc.materials.size());
  for (const GltfJson& material : doc.materials) out.push_back(readMaterial(doc, material, reader));
  return out;
}

}  // namespace prism
