#include "parse/ObjMaterials.h"

#include <algorithm>
#include <filesystem>
#include <unordered_map>

#include "parse/PrintableText.h"

namespace prism {

namespace {

std::string folderOf(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

bool isBlank(char c) {
  return c == ' ' || c == '\t';
}

std::vector<std::string_view> wordsOf(std::string_view text) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isBlank(text[i])) ++i;
    const size_t begin = i;
    while (i < text.size() && !isBlank(text[i])) ++i;
    if (i > begin) words.push_back(text.substr(begin, i - begin));
  }
  return words;
}

// The material faces get where they name none, or one no library defines: Prism's default.
MaterialDesc defaultMaterial(const std::string& objPath) {
  MaterialDesc material;
  material.name = "default (" + std::filesystem::path(objPath).filename().string() + ")";
  material.loc = FileLoc{objPath};
  return material;
}

}  // namespace

ObjMaterials::ObjMaterials(const std::string& objPath, const CompanionFiles& files,
                           std::vector<std::string>& warnings)
    : objPath_(objPath), folder_(folderOf(objPath)), files_(files), warnings_(warnings) {}

void ObjMaterials::readLibraries(std::string_view names, uint64_t line, int column) {
  if (names.empty()) {
    if (warnedOnce("")) return;
    warnings_.push_back(objPath_ + ":" + std::to_string(line) +
                        ": mtllib names no file; it is skipped");
    return;
  }
  const CompanionFile whole = findCompanionFile(names, folder_, files_);
  if (!whole.found.empty()) return readLibrary(whole.found, line, column);
  const std::vector<std::string_view> words = wordsOf(names);
  std::vector<CompanionFile> found;
  bool any = false;
  for (const std::string_view word : words) {
    found.push_back(findCompanionFile(word, folder_, files_));
    any = any || !found.back().found.empty();
  }
  if (!any && words.size() > 1) return warnMissing(names, whole.lookedFor, line);
  for (size_t i = 0; i < words.size(); ++i) {
    if (found[i].found.empty()) {
      warnMissing(words[i], found[i].lookedFor, line);
    } else {
      readLibrary(found[i].found, line, column);
    }
  }
}

void ObjMaterials::warnMissing(std::string_view name, const std::string& lookedFor, uint64_t line) {
  if (warnedOnce(std::string(name))) return;
  warnings_.push_back(objPath_ + ":" + std::to_string(line) + ": material library '" +
                      printableExcerpt(name, 200) + "' not found (looked for '" + lookedFor +
                      "'); faces that use its materials get the default material");
}

bool ObjMaterials::warnedOnce(const std::string& library) {
  return !missing_.insert(library).second;
}

void ObjMaterials::readLibrary(const std::string& file, uint64_t line, int column) {
  if (std::find(read_.begin(), read_.end(), file) != read_.end()) return;
  read_.push_back(file);
  const std::string text = files_.readText(file, FileLoc{objPath_, static_cast<int>(line), column});
  MtlLibrary library = parseMtl(text, file);
  for (std::string& warning : library.warnings) warnings_.push_back(std::move(warning));
  for (MtlMaterial& material : library.materials) {
    if (names_.add(material.material.name).second) {
      materials_.push_back(std::move(material));
      continue;
    }
    const std::string& name = material.material.name;
    if (std::find(redefined_.begin(), redefined_.end(), name) != redefined_.end()) continue;
    redefined_.push_back(name);
    warnings_.push_back(material.material.loc.file + ":" +
                        std::to_string(material.material.loc.line) + ": material '" +
                        printableExcerpt(name, 200) +
                        "' is defined again; the first definition is used");
  }
}

std::vector<MaterialId> ObjMaterials::addUsed(const std::vector<bool>& used, bool defaultUsed,
                                              ModelDesc& model, const MemoryLimit& limit) const {
  std::vector<MaterialId> index(materials_.size() + 1, 0);
  std::unordered_map<std::string, uint32_t> textureOf;  // by file, each read once
  for (size_t n = 0; n < materials_.size(); ++n) {
    if (!used[n]) continue;
    index[n] = static_cast<MaterialId>(model.materials.size());
    MaterialDesc material = materials_[n].material;
    if (const std::optional<MtlTextureRef>& ref = materials_[n].diffuseMap) {
      const CompanionFile file = findCompanionFile(ref->file, folderOf(ref->loc.file), files_);
      if (file.found.empty()) {
        model.warnings.push_back(ref->loc.file + ":" + std::to_string(ref->loc.line) +
                                 ": texture '" + printableExcerpt(ref->file, 200) +
                                 "' not found (looked for '" + file.lookedFor + "'); material '" +
                                 printableExcerpt(material.name, 200) +
                                 "' shows its diffuse colour without it");
      } else {
        const auto [it, added] =
            textureOf.try_emplace(file.found, static_cast<uint32_t>(model.textures.size()));
        if (added) model.textures.push_back(files_.readTexture(file.found, ref->loc, limit));
        material.diffuseMap = ref->map;
        material.diffuseMap->texture = it->second;
      }
    }
    model.materials.push_back(std::move(material));
  }
  if (defaultUsed) {
    index.back() = static_cast<MaterialId>(model.materials.size());
    model.materials.push_back(defaultMaterial(objPath_));
  }
  return index;
}

}  // namespace prism
