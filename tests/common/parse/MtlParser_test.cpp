#include "parse/MtlParser.h"

#include <gtest/gtest.h>

#include <string_view>

namespace prism {
namespace {

const MtlMaterial& only(const MtlLibrary& library) {
  EXPECT_EQ(library.materials.size(), 1u);
  return library.materials.at(0);
}

// One material with the given illum and the colours every illum reads.
MaterialDesc withIllum(int illum, std::string_view extra = "") {
  std::string text = "newmtl m\nKa 0.1 0.2 0.3\nKd 0.4 0.5 0.6\nKs 0.7 0.8 0.9\nNs 50\nNi 1.33\n";
  text += extra;
  text += "illum " + std::to_string(illum) + "\n";
  return only(parseMtl(text, "t.mtl")).material;
}

TEST(MtlParser, ReadsEveryColourAndNumberOfAPlainMaterial) {
  const MtlLibrary library = parseMtl(
      "# exported\nnewmtl Material.001\nNs 96.078431\nKa 1.000000 1.000000 1.000000\n"
      "Kd 0.640000 0.320000 0.160000\nKs 0.5 0.5 0.5\nNi 1.000000\nd 1.000000\nillum 2\n",
      "scene.mtl");
  EXPECT_TRUE(library.warnings.empty());
  const MaterialDesc& m = only(library).material;
  EXPECT_EQ(m.name, "Material.001");
  EXPECT_EQ(m.loc.file, "scene.mtl");
  EXPECT_EQ(m.loc.line, 2);
  EXPECT_EQ(m.ambient, Color(1.0f));
  EXPECT_EQ(m.diffuse, Color(0.64f, 0.32f, 0.16f));
  EXPECT_EQ(m.specular, Color(0.5f));
  EXPECT_FLOAT_EQ(m.shininess, 96.078431f);
  EXPECT_EQ(m.reflectance, Color(0.0f));
  EXPECT_EQ(m.transmittance, Color(0.0f));
  EXPECT_FALSE(m.diffuseMap);
  EXPECT_FALSE(only(library).diffuseMap);
}

TEST(MtlParser, AbsentStatementsKeepPrismsDefaultsAndOneNumberIsGrey) {
  const MaterialDesc m = only(parseMtl("newmtl bare\nKs 0.25\n", "t.mtl")).material;
  EXPECT_EQ(m.diffuse, Color(0.8f));
  EXPECT_EQ(m.ambient, Color(0.0f));
  EXPECT_EQ(m.specular, Color(0.25f));  // no illum: 2, the highlight is on
  EXPECT_FLOAT_EQ(m.shininess, 32.0f);
  EXPECT_FLOAT_EQ(m.ior, 1.5f);
}

TEST(MtlParser, TheIllumTableMapsEachModelOntoPrism) {
  const Color ka(0.1f, 0.2f, 0.3f), ks(0.7f, 0.8f, 0.9f), none(0.0f);
  // Glass lets through 1 − d (no Tf here); the mirror glasses 4 and 6 keep back what they
  // reflect.
  const Color through(0.25f), mirroredThrough = (Color(1.0f) - ks) * through;
  struct Row {
    int illum;
    Color ambient, specular, reflectance;
    bool glass;
    Color transmittance;
    bool fresnel;
  };
  const Row table[] = {
      {0, none, none, none, false, none, false},
      {1, ka, none, none, false, none, false},
      {2, ka, ks, none, false, none, false},
      {3, ka, ks, ks, false, none, false},
      {4, ka, ks, ks, true, mirroredThrough, false},
      {5, ka, ks, ks, false, none, false},
      {6, ka, ks, ks, true, mirroredThrough, false},
      {7, ka, ks, none, true, through, true},  // reflects by the Fresnel share of its transmittance
      {8, ka, ks, ks, false, none, false},
      {9, ka, ks, none, true, through, false},
  };
  for (const Row& row : table) {
    SCOPED_TRACE("illum " + std::to_string(row.illum));
    const MaterialDesc m = withIllum(row.illum, "d 0.75\n");
    if (row.glass) {
      // Glass keeps its colours and bends by Ni.
      EXPECT_EQ(m.ambient, row.ambient);
      EXPECT_EQ(m.specular, row.specular);
      EXPECT_EQ(m.reflectance, row.reflectance);
      EXPECT_EQ(m.diffuse, Color(0.4f, 0.5f, 0.6f));
      EXPECT_EQ(m.transmittance, row.transmittance);
      EXPECT_FLOAT_EQ(m.ior, 1.33f);
      EXPECT_EQ(m.fresnel, row.fresnel);
    } else {
      // Dissolve elsewhere: a quarter shows through unbent, the surface's own light fades.
      EXPECT_EQ(m.ambient, row.ambient * 0.75f);
      EXPECT_EQ(m.specular, row.specular * 0.75f);
      EXPECT_EQ(m.reflectance, row.reflectance * 0.75f);
      EXPECT_EQ(m.diffuse, Color(0.4f, 0.5f, 0.6f) * 0.75f);
      EXPECT_EQ(m.transmittance, Color(0.25f));
      EXPECT_FLOAT_EQ(m.ior, 1.0f);
      EXPECT_FALSE(m.fresnel);
    }
  }
}

TEST(MtlParser, OpaqueMaterialsTransmitNothingAndGlassTakesTf) {
  EXPECT_EQ(withIllum(3).transmittance, Color(0.0f));
  EXPECT_EQ(withIllum(3).reflectance, Color(0.7f, 0.8f, 0.9f));
  EXPECT_EQ(withIllum(7).transmittance, Color(0.0f));  // d 1 and no Tf: glass lets nothing through
  const MaterialDesc glass = withIllum(7, "Tf 0.9 1 0.8\nd 0.5\n");
  EXPECT_EQ(glass.transmittance, Color(0.9f, 1.0f, 0.8f));
  EXPECT_EQ(glass.reflectance, Color(0.0f));
  EXPECT_TRUE(glass.fresnel);
  // Clear Fresnel glass as exporters write it (Kd 0, Ks 1, Tf 1, illum 7) conserves energy: all
  // of it is split between reflection and refraction, nothing reflected twice.
  const MaterialDesc clear =
      only(parseMtl("newmtl glass\nKd 0\nKs 1\nNs 200\nNi 1.5\nd 0\nTf 1\nillum 7\n", "g.mtl"))
          .material;
  EXPECT_EQ(clear.transmittance, Color(1.0f));
  EXPECT_EQ(clear.reflectance, Color(0.0f));
  EXPECT_EQ(clear.diffuse, Color(0.0f));
  EXPECT_EQ(withIllum(6, "Tf 1\n").transmittance, Color(1.0f) - Color(0.7f, 0.8f, 0.9f));
  EXPECT_EQ(withIllum(2, "Tr 0.25\n").transmittance, Color(0.25f));  // Tr = 1 - d
  EXPECT_EQ(withIllum(2, "Tf 0.5\n").transmittance, Color(0.0f));    // Tf only for glass
}

TEST(MtlParser, Illum10AndUnknownIllumsAreShadedAsTwoWithAWarning) {
  const MtlLibrary library =
      parseMtl("newmtl a\nKs 1\nillum 10\nnewmtl b\nKs 1\nillum 12\n", "t.mtl");
  ASSERT_EQ(library.materials.size(), 2u);
  for (const MtlMaterial& m : library.materials) {
    EXPECT_EQ(m.material.specular, Color(1.0f));
    EXPECT_EQ(m.material.reflectance, Color(0.0f));
  }
  EXPECT_EQ(library.warnings,
            (std::vector<std::string>{
                "t.mtl:3: illum 10 (shadows cast onto invisible surfaces) is not modelled; it is "
                "shaded as illum 2",
                "t.mtl:6: illum 12 is not one of Wavefront's 0 to 10; it is shaded as illum 2"}));
}

TEST(MtlParser, DiffuseMapKeepsScaleAndOffsetAndNamesTheOptionsItSkips) {
  const MtlLibrary library = parseMtl(
      "newmtl a\nmap_Kd -clamp on -s 2 3 1 -mm 0 1 -o 0.25 0.5 -t 1 1 my texture\\wood.png\n"
      "newmtl b\nmap_Kd -clamp off plain.png\n",
      "dir/t.mtl");
  ASSERT_EQ(library.materials.size(), 2u);
  const std::optional<MtlTextureRef>& map = library.materials[0].diffuseMap;
  ASSERT_TRUE(map);
  EXPECT_EQ(map->file, "my texture/wood.png");
  EXPECT_EQ(map->map.scale, Vec2(2.0f, 3.0f));
  EXPECT_EQ(map->map.offset, Vec2(0.25f, 0.5f));
  EXPECT_EQ(map->loc.file, "dir/t.mtl");
  EXPECT_EQ(map->loc.line, 2);
  EXPECT_EQ(map->loc.column, 54);
  EXPECT_EQ(library.materials[1].diffuseMap->file, "plain.png");
  EXPECT_EQ(library.materials[1].diffuseMap->map.scale, Vec2(1.0f));
  // Each skipped option once, at its first line.
  EXPECT_EQ(library.warnings,
            (std::vector<std::string>{
                "dir/t.mtl:2: map_Kd option -clamp is not modelled; the texture is read without "
                "it (repeating, as the file's pixels are)",
                "dir/t.mtl:2: map_Kd option -mm is not modelled; the texture is read without it "
                "(repeating, as the file's pixels are)",
                "dir/t.mtl:2: map_Kd option -t is not modelled; the texture is read without it "
                "(repeating, as the file's pixels are)"}));
}

TEST(MtlParser, StatementsPrismDoesNotModelAreWarnedOnceEach) {
  const MtlLibrary library = parseMtl(
      "newmtl a\nKe 1 1 1\nmap_Bump -bm 0.5 n.png\nmap_Ks s.png\nPr 0.5\nnewmtl b\nKe 0 0 0\n"
      "bump b.png\nfrobnicate 3\n",
      "t.mtl");
  EXPECT_EQ(library.materials.size(), 2u);
  EXPECT_EQ(library.warnings,
            (std::vector<std::string>{
                "t.mtl:2: 'Ke' (emission) is not modelled by Prism; it is skipped",
                "t.mtl:3: 'map_Bump' (bump map) is not modelled by Prism; it is skipped",
                "t.mtl:4: 'map_Ks' (specular texture) is not modelled by Prism; it is skipped",
                "t.mtl:5: 'Pr' (PBR roughness) is not modelled by Prism; it is skipped",
                "t.mtl:8: 'bump' (bump map) is not modelled by Prism; it is skipped",
                "t.mtl:9: unknown statement 'frobnicate' is skipped"}));
}

TEST(MtlParser, KeywordsAreReadInAnyCaseAndLinesEndAnyWay) {
  const MtlLibrary library =
      parseMtl("NEWMTL x\r\nkd 0.5 0.25 0.125 # a comment\rMAP_KD Tex.PNG\r\n", "t.mtl");
  const MtlMaterial& m = only(library);
  EXPECT_EQ(m.material.name, "x");
  EXPECT_EQ(m.material.diffuse, Color(0.5f, 0.25f, 0.125f));
  ASSERT_TRUE(m.diffuseMap);
  EXPECT_EQ(m.diffuseMap->file, "Tex.PNG");
  EXPECT_EQ(m.diffuseMap->loc.line, 3);
}

TEST(MtlParser, NamesMayHoldBlanks) {
  EXPECT_EQ(only(parseMtl("newmtl  my material  # comment\n", "t.mtl")).material.name,
            "my material");
}

TEST(MtlParser, SpectralColoursAndHaloAreWarnedAndTheRestRead) {
  const MtlLibrary library =
      parseMtl("newmtl a\nKd spectral ident.rfl 1\nKa xyz 1 1 1\nd -halo 0.5\n", "t.mtl");
  const MaterialDesc& m = only(library).material;
  EXPECT_EQ(m.transmittance, Color(0.5f));  // d 0.5 is still read
  EXPECT_EQ(library.warnings.size(), 3u);
  EXPECT_EQ(library.warnings[0],
            "t.mtl:2: Kd spectral is not read; the material keeps its default Kd");
  EXPECT_EQ(library.warnings[2],
            "t.mtl:4: d -halo is not modelled; the dissolve is the same at every angle");
}

TEST(MtlParser, IndexBelowOneIsRaisedToOneWithAWarningWhereItBendsLight) {
  const MtlLibrary opaque = parseMtl("newmtl a\nNi 0\nillum 2\n", "t.mtl");
  EXPECT_TRUE(opaque.warnings.empty());
  EXPECT_FLOAT_EQ(only(opaque).material.ior, 1.0f);
  const MtlLibrary glass = parseMtl("newmtl a\nNi 0.5\nd 0.5\nillum 7\n", "t.mtl");
  EXPECT_FLOAT_EQ(only(glass).material.ior, 1.0f);
  EXPECT_EQ(glass.warnings, std::vector<std::string>{
                                "t.mtl:2: Ni 0.5 is below 1 (the outside's index); 1 is used"});
}

TEST(MtlParser, StatementsBeforeTheFirstMaterialAreWarnedOnce) {
  const MtlLibrary library = parseMtl("Kd 1 0 0\nKs 1\nnewmtl a\n", "t.mtl");
  EXPECT_EQ(only(library).material.diffuse, Color(0.8f));
  EXPECT_EQ(library.warnings,
            std::vector<std::string>{
                "t.mtl:1: 'Kd' before the first newmtl belongs to no material; it is skipped"});
}

struct BadMtl {
  const char* name;
  const char* text;
  int line;
  int column;
  const char* message;
};

const BadMtl kBadMtl[] = {
    {"letter", "newmtl a\nKd 0.5 x 0.5\n", 2, 8, "expected a number but found 'x'"},
    {"negative", "newmtl a\nKd 1 -1 0\n", 2, 6, "Kd must not be negative"},
    {"two_numbers", "newmtl a\nKs 1 1\n", 2, 1, "Ks takes 1 or 3 numbers"},
    {"four_numbers", "newmtl a\nKa 1 1 1 1\n", 2, 10, "Ka takes 1 or 3 numbers"},
    {"no_number", "newmtl a\nKd\n", 2, 1, "Kd needs 1 or 3 numbers"},
    {"huge", "newmtl a\nNs 1e39\n", 2, 4, "non-finite number '1e39'"},
    {"nan", "newmtl a\nNi nan\n", 2, 4, "non-finite number 'nan'"},
    {"negative_shininess", "newmtl a\nNs -2\n", 2, 1, "Ns must not be negative"},
    {"dissolve_above_one", "newmtl a\nd 1.5\n", 2, 3, "d must be between 0 and 1"},
    {"transparency_below_zero", "newmtl a\nTr -0.5\n", 2, 4, "Tr must be between 0 and 1"},
    {"two_dissolves", "newmtl a\nd 0.5 0.5\n", 2, 7, "d takes one number"},
    {"illum_word", "newmtl a\nillum two\n", 2, 7,
     "expected an illum integer from 0 to 10 but found 'two'"},
    {"illum_fraction", "newmtl a\nillum 2.5\n", 2, 7, "expected an illum integer"},
    {"newmtl_without_name", "newmtl\n", 1, 1, "newmtl needs a name"},
    {"map_without_file", "newmtl a\nmap_Kd -s 2 2\n", 2, 1, "map_Kd needs a file name"},
    {"option_without_number", "newmtl a\nmap_Kd -o x.png\n", 2, 8,
     "map_Kd option -o needs a number"},
    {"option_without_value", "newmtl a\nmap_Kd -clamp\n", 2, 8,
     "map_Kd option -clamp needs 1 value"},
    {"crlf_letter", "newmtl a\r\nKd 1 1 1\r\nNs 1O\r\n", 3, 4, "expected a number but found '1O'"},
};

class MtlBadInput : public testing::TestWithParam<BadMtl> {};

TEST_P(MtlBadInput, FailsAtTheWordAtFault) {
  const BadMtl& bad = GetParam();
  try {
    parseMtl(bad.text, "bad.mtl");
    FAIL() << bad.name << " parsed without error";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "bad.mtl");
    EXPECT_EQ(error.loc().line, bad.line) << error.what();
    EXPECT_EQ(error.loc().column, bad.column) << error.what();
    EXPECT_NE(error.message().find(bad.message), std::string::npos) << error.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Mtl, MtlBadInput, testing::ValuesIn(kBadMtl),
                         [](const testing::TestParamInfo<BadMtl>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace prism
