#include "parse/MtlParser.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>

#include "parse/LineChunks.h"
#include "parse/PrintableText.h"

namespace prism {

namespace {

// The values an MTL material gives, before the illum table turns them into a Prism material.
// Absent statements keep Prism's defaults (docs/scene-format.md, "MTL materials").
struct MtlValues {
  Color ka{0.0f};
  Color kd{0.8f};
  Color ks{0.0f};
  float ns = 32.0f;
  float ni = 1.5f;
  FileLoc niLoc;
  float d = 1.0f;
  std::optional<Color> tf;
  int illum = 2;
};

// illum 7's reflection is the Fresnel share of its transmittance (MaterialDesc::fresnel), not Ks:
// both would reflect the light twice.
bool reflectsByKs(int illum) {
  return illum == 3 || illum == 4 || illum == 5 || illum == 6 || illum == 8;
}
bool isGlass(int illum) {
  return illum == 4 || illum == 6 || illum == 7 || illum == 9;
}

std::string lowercase(std::string_view word) {
  std::string s(word);
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// What the statements Prism reads past are, for their warning.
const char* unmodelledStatement(const std::string& keyword) {
  static const struct {
    const char* keyword;
    const char* what;
  } kKnown[] = {
      {"ke", "emission"},
      {"map_ka", "ambient texture"},
      {"map_ks", "specular texture"},
      {"map_ns", "shininess texture"},
      {"map_d", "dissolve texture"},
      {"map_tr", "transparency texture"},
      {"map_bump", "bump map"},
      {"bump", "bump map"},
      {"map_kn", "normal map"},
      {"norm", "normal map"},
      {"disp", "displacement map"},
      {"decal", "decal texture"},
      {"refl", "reflection map"},
      {"map_refl", "reflection map"},
      {"map_ke", "emission texture"},
      {"sharpness", "reflection sharpness"},
      {"km", "bump multiplier"},
      {"pr", "PBR roughness"},
      {"pm", "PBR metallic"},
      {"ps", "PBR sheen"},
      {"pc", "PBR clearcoat"},
      {"pcr", "PBR clearcoat roughness"},
      {"aniso", "PBR anisotropy"},
      {"anisor", "PBR anisotropy rotation"},
      {"map_pr", "PBR roughness texture"},
      {"map_pm", "PBR metallic texture"},
      {"map_ps", "PBR sheen texture"},
  };
  for (const auto& known : kKnown) {
    if (keyword == known.keyword) return known.what;
  }
  return nullptr;
}

// How many values each map_Kd option takes (-s, -o and -t: one to three numbers).
int optionArguments(const std::string& option) {
  if (option == "-blendu" || option == "-blendv" || option == "-bm" || option == "-boost" ||
      option == "-cc" || option == "-clamp" || option == "-imfchan" || option == "-texres" ||
      option == "-type") {
    return 1;
  }
  if (option == "-mm") return 2;
  if (option == "-s" || option == "-o" || option == "-t") return 3;
  return -1;
}

// The shortest text that reads back as value.
std::string shortNumber(float value) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
  return std::string(text, ec == std::errc() ? end : text);
}

struct MtlFailure {
  const char* at;
  std::string message;
};

class MtlReader {
 public:
  MtlReader(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  MtlLibrary read() {
    const char* p = text_.data();
    const char* const end = p + text_.size();
    try {
      while (p < end) {
        ++line_;
        lineStart_ = p;
        const char* next = nextLineStart(p, end);
        lineEnd_ = next;
        while (lineEnd_ > p && (lineEnd_[-1] == '\n' || lineEnd_[-1] == '\r')) --lineEnd_;
        statement(p);
        p = next;
      }
    } catch (const MtlFailure& failure) {
      throw SceneError(FileLoc{path_, line_, static_cast<int>(failure.at - lineStart_) + 1},
                       failure.message);
    }
    finishMaterial();
    return std::move(library_);
  }

 private:
  static bool isBlank(char c) { return c == ' ' || c == '\t'; }

  // The next word of the line from p (null where the line or a comment begins), and past it.
  const char* nextWord(const char* p) const {
    while (p < lineEnd_ && isBlank(*p)) ++p;
    return (p == lineEnd_ || *p == '#') ? nullptr : p;
  }
  const char* wordEnd(const char* p) const {
    while (p < lineEnd_ && !isBlank(*p)) ++p;
    return p;
  }
  // The rest of the line from p, blanks trimmed at both ends and a trailing comment dropped: a
  // name or a file name, which may hold blanks.
  std::string_view restOfLine(const char* p) const {
    const char* first = nextWord(p);
    if (!first) return {};
    const char* last = first;
    for (const char* q = first; q < lineEnd_;) {
      const char* word = nextWord(q);
      if (!word) break;
      q = wordEnd(word);
      last = q;
    }
    return std::string_view(first, static_cast<size_t>(last - first));
  }

  void warnOnce(const std::string& kind, const std::string& message) {
    if (warned_.insert(kind).second) {
      library_.warnings.push_back(path_ + ":" + std::to_string(line_) + ": " + message);
    }
  }

  void statement(const char* p) {
    const char* word = nextWord(p);
    if (!word) return;
    p = wordEnd(word);
    const std::string keyword = lowercase(std::string_view(word, static_cast<size_t>(p - word)));
    if (keyword == "newmtl") return newMaterial(word, p);
    if (!current_) {
      warnOnce("outside", "'" + printableExcerpt(std::string_view(word, p - word)) +
                              "' before the first newmtl belongs to no material; it is skipped");
      return;
    }
    MtlValues& v = values_;
    if (keyword == "ka") {
      colour(word, p, v.ka, "Ka");
    } else if (keyword == "kd") {
      colour(word, p, v.kd, "Kd");
    } else if (keyword == "ks") {
      colour(word, p, v.ks, "Ks");
    } else if (keyword == "tf") {
      Color tf = v.tf.value_or(Color(1.0f));
      if (colour(word, p, tf, "Tf")) v.tf = tf;
    } else if (keyword == "ns") {
      v.ns = oneNumber(word, p, "Ns");
      if (v.ns < 0.0f) throw MtlFailure{word, "Ns must not be negative"};
    } else if (keyword == "ni") {
      v.ni = oneNumber(word, p, "Ni");
      if (v.ni < 0.0f) throw MtlFailure{word, "Ni must not be negative"};
      v.niLoc = FileLoc{path_, line_, 0};
    } else if (keyword == "d" || keyword == "tr") {
      dissolve(word, p, keyword == "tr");
    } else if (keyword == "illum") {
      illum(word, p);
    } else if (keyword == "map_kd") {
      diffuseMap(word, p);
    } else if (const char* what = unmodelledStatement(keyword)) {
      warnOnce(keyword, "'" + std::string(word, p) + "' (" + what +
                            ") is not modelled by Prism; it is skipped");
    } else {
      warnOnce(keyword, "unknown statement '" + printableExcerpt(std::string_view(word, p - word)) +
                            "' is skipped");
    }
  }

  void newMaterial(const char* word, const char* p) {
    finishMaterial();
    const std::string_view name = restOfLine(p);
    if (name.empty()) throw MtlFailure{word, "newmtl needs a name"};
    current_ = MtlMaterial{};
    current_->material.name = std::string(name);
    current_->material.loc = FileLoc{path_, line_, static_cast<int>(word - lineStart_) + 1};
    values_ = MtlValues{};
  }

  // A number word: what std::from_chars reads as a double (after an optional '+'), finite as a
  // float.
  static bool isNumber(const char* word, const char* end) {
    double value = 0.0;
    const char* first = word + (*word == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, end, value);
    return ec == std::errc() && ptr == end;
  }
  static float number(const char* word, const char* end) {
    const std::string_view w(word, static_cast<size_t>(end - word));
    double value = 0.0;
    const char* first = word + (*word == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, end, value);
    const auto rounded = static_cast<float>(value);
    if (ec == std::errc::result_out_of_range ||
        (ec == std::errc() && ptr == end && !std::isfinite(rounded))) {
      throw MtlFailure{word, "non-finite number '" + printableExcerpt(w) + "'"};
    }
    if (ec != std::errc() || ptr != end) {
      throw MtlFailure{word, "expected a number but found '" + printableExcerpt(w) + "'"};
    }
    return rounded;
  }

  float oneNumber(const char* statement, const char* p, const char* what) {
    const char* word = nextWord(p);
    if (!word) throw MtlFailure{statement, std::string(what) + " needs a number"};
    p = wordEnd(word);
    const float value = number(word, p);
    if (const char* extra = nextWord(p)) {
      throw MtlFailure{extra, std::string(what) + " takes one number"};
    }
    return value;
  }

  // "K? r [g b]" (one number: grey), or "K? spectral file" / "K? xyz x y z", which are named in
  // a warning. False where the colour was not read.
  bool colour(const char* statement, const char* p, Color& out, const char* what) {
    const char* word = nextWord(p);
    if (!word) throw MtlFailure{statement, std::string(what) + " needs 1 or 3 numbers"};
    const std::string first = lowercase(std::string_view(word, wordEnd(word) - word));
    if (first == "spectral" || first == "xyz") {
      warnOnce(
          std::string(what) + first,
          std::string(what) + " " + first + " is not read; the material keeps its default " + what);
      return false;
    }
    float rgb[3] = {0, 0, 0};
    int count = 0;
    for (const char* w = word; w; w = nextWord(p)) {
      p = wordEnd(w);
      const float value = number(w, p);
      if (count == 3) throw MtlFailure{w, std::string(what) + " takes 1 or 3 numbers"};
      if (value < 0.0f) throw MtlFailure{w, std::string(what) + " must not be negative"};
      rgb[count++] = value;
    }
    if (count == 2) throw MtlFailure{statement, std::string(what) + " takes 1 or 3 numbers"};
    out = count == 1 ? Color(rgb[0]) : Color(rgb[0], rgb[1], rgb[2]);
    return true;
  }

  // "d [-halo] factor" or "Tr factor" (Tr = 1 − d).
  void dissolve(const char* statement, const char* p, bool transparency) {
    const char* word = nextWord(p);
    if (word && !transparency &&
        lowercase(std::string_view(word, wordEnd(word) - word)) == "-halo") {
      warnOnce("-halo", "d -halo is not modelled; the dissolve is the same at every angle");
      p = wordEnd(word);
    }
    const char* at = nextWord(p);
    const float value = oneNumber(statement, p, transparency ? "Tr" : "d");
    if (value < 0.0f || value > 1.0f) {
      throw MtlFailure{at ? at : statement,
                       std::string(transparency ? "Tr" : "d") + " must be between 0 and 1"};
    }
    values_.d = transparency ? 1.0f - value : value;
  }

  void illum(const char* statement, const char* p) {
    const char* word = nextWord(p);
    if (!word) throw MtlFailure{statement, "illum needs an integer from 0 to 10"};
    const char* end = wordEnd(word);
    int value = 0;
    const auto [ptr, ec] = std::from_chars(word, end, value);
    if (ec != std::errc() || ptr != end) {
      throw MtlFailure{word, "expected an illum integer from 0 to 10 but found '" +
                                 printableExcerpt(std::string_view(word, end - word)) + "'"};
    }
    if (const char* extra = nextWord(end)) throw MtlFailure{extra, "illum takes one integer"};
    if (value == 10) {
      warnOnce("illum10",
               "illum 10 (shadows cast onto invisible surfaces) is not modelled; it is shaded "
               "as illum 2");
      value = 2;
    } else if (value < 0 || value > 10) {
      warnOnce("illum-range", "illum " + std::to_string(value) +
                                  " is not one of Wavefront's 0 to 10; it is shaded as illum 2");
      value = 2;
    }
    values_.illum = value;
  }

  // "map_Kd [-option values ...] file".
  void diffuseMap(const char* statement, const char* p) {
    MtlTextureRef ref;
    for (;;) {
      const char* word = nextWord(p);
      if (!word || *word != '-') break;
      const char* end = wordEnd(word);
      const std::string option = lowercase(std::string_view(word, end - word));
      const int arguments = optionArguments(option);
      if (arguments < 0) break;  // not an option: a file name that starts with '-'
      p = end;
      if (option == "-s" || option == "-o" || option == "-t") {
        float uvw[3] = {option == "-s" ? 1.0f : 0.0f, option == "-s" ? 1.0f : 0.0f, 0.0f};
        int count = 0;
        for (const char* w = nextWord(p); w && count < 3; w = nextWord(p)) {
          const char* wEnd = wordEnd(w);
          if (!isNumber(w, wEnd)) break;
          uvw[count++] = number(w, wEnd);
          p = wEnd;
        }
        if (count == 0) throw MtlFailure{word, "map_Kd option " + option + " needs a number"};
        if (option == "-s") ref.map.scale = Vec2(uvw[0], uvw[1]);
        if (option == "-o") ref.map.offset = Vec2(uvw[0], uvw[1]);
        if (option != "-t") continue;
      } else {
        for (int k = 0; k < arguments; ++k) {
          const char* w = nextWord(p);
          if (!w) {
            throw MtlFailure{word, "map_Kd option " + option + " needs " +
                                       std::to_string(arguments) + " value" +
                                       (arguments > 1 ? "s" : "")};
          }
          p = wordEnd(w);
        }
      }
      warnOnce("map_Kd" + option, "map_Kd option " + option +
                                      " is not modelled; the texture is read without it "
                                      "(repeating, as the file's pixels are)");
    }
    const std::string_view file = restOfLine(p);
    if (file.empty()) throw MtlFailure{statement, "map_Kd needs a file name"};
    ref.file = std::string(file);
    std::replace(ref.file.begin(), ref.file.end(), '\\', '/');
    ref.loc = FileLoc{path_, line_, static_cast<int>(nextWord(p) - lineStart_) + 1};
    current_->diffuseMap = std::move(ref);
  }

  // Turns the values of the material read so far into Prism's, by the illum table (MtlParser.h).
  void finishMaterial() {
    if (!current_) return;
    const MtlValues& v = values_;
    MaterialDesc& m = current_->material;
    m.ambient = v.illum == 0 ? Color(0.0f) : v.ka;
    m.diffuse = v.kd;
    m.specular = v.illum >= 2 ? v.ks : Color(0.0f);
    m.shininess = v.ns;
    m.reflectance = reflectsByKs(v.illum) ? v.ks : Color(0.0f);
    if (isGlass(v.illum)) {
      // What the glass lets through: Tf, else what the dissolve does not stop; the mirror illums
      // 4 and 6 keep back what they reflect, (1 − Ks), as Wavefront's illum 6 equation does.
      const Color through = v.tf.value_or(Color(1.0f - v.d));
      const bool mirrored = v.illum == 4 || v.illum == 6;
      m.transmittance = mirrored ? glm::max(Color(1.0f) - v.ks, Color(0.0f)) * through : through;
      m.fresnel = v.illum == 7;
      m.ior = std::max(v.ni, 1.0f);
      if (v.ni < 1.0f && warned_.insert("ni").second) {  // at the first glass that needs it
        library_.warnings.push_back(v.niLoc.file + ":" + std::to_string(v.niLoc.line) + ": Ni " +
                                    shortNumber(v.ni) +
                                    " is below 1 (the outside's index); 1 is used");
      }
    } else {
      m.ior = std::max(v.ni, 1.0f);
      if (v.d < 1.0f) {
        // Dissolve: the surface's own light fades by d and 1 − d of what lies behind shows
        // through, unbent.
        m.ambient *= v.d;
        m.diffuse *= v.d;
        m.specular *= v.d;
        m.reflectance *= v.d;
        m.transmittance = Color(1.0f - v.d);
        m.ior = 1.0f;
        m.fresnel = false;
      }
    }
    library_.materials.push_back(std::move(*current_));
    current_.reset();
  }

  std::string_view text_;
  const std::string& path_;
  int line_ = 0;
  const char* lineStart_ = nullptr;
  const char* lineEnd_ = nullptr;
  std::optional<MtlMaterial> current_;
  MtlValues values_;
  MtlLibrary library_;
  std::set<std::string> warned_;
};

}  // namespace

MtlLibrary parseMtl(std::string_view text, const std::string& path) {
  return MtlReader(text, path).read();
}

}  // namespace prism
