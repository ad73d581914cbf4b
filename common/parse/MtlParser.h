// Wavefront MTL material libraries, the .mtl files an OBJ names with 'mtllib', mapped onto
// Prism's Phong materials by one rule (docs/scene-format.md, "MTL materials"):
//
//   Ka → ambient, Kd → diffuse, Ks → specular (and the mirror's tint where illum reflects),
//   Ns → shininess, Ni → ior, d (or Tr = 1 − d) and Tf → transmittance, map_Kd → diffuseMap.
//
//   illum  Wavefront's meaning                      Prism
//   0      colour, ambient off                      diffuse only: no ambient, no highlight
//   1      colour, ambient on                       ambient and diffuse, no highlight
//   2      highlight on (also: no illum given)      + specular Ks, shininess Ns
//   3      reflection, ray traced                   + reflectance Ks: a mirror tinted by Ks
//   4      glass, reflection ray traced             as 3 + transmittance (1 − Ks)·T, ior Ni,
//                                                     fresnel off
//   5      Fresnel reflection, ray traced           as 3 (Prism's Fresnel splits transmission)
//   6      refraction, no Fresnel, ray traced       as 4
//   7      refraction and Fresnel, ray traced       as 2 + transmittance T, ior Ni, fresnel on:
//                                                     its reflection is the Fresnel share of T
//   8      reflection, not ray traced               as 3 (Prism always traces)
//   9      glass, reflection not ray traced         as 2 + transmittance T, ior Ni, fresnel off
//   10     shadows onto invisible surfaces          as 2, named in a warning
//
// T, what the glass illums (4, 6, 7, 9) let through, is Tf where the material gives it,
// otherwise 1 − d. On the other illums a dissolve d < 1 lets 1 − d through unbent (ior 1, no
// Fresnel) and scales the surface's own colours by d. Statements Prism does not model (Ke,
// map_Bump, map_Ks, the PBR extensions, ...) and options of map_Kd other than -s and -o are named
// in a warning, each kind once; only malformed numbers are errors.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/SceneDescription.h"

namespace prism {

// A map_Kd statement: the texture's file as written and where it is placed.
struct MtlTextureRef {
  std::string file;  // the rest of the line after the options, '\' turned into '/'
  TextureMap map;    // scale and offset from -s and -o; `texture` is set by whoever loads it
  FileLoc loc;       // the file name's first character
};

struct MtlMaterial {
  MaterialDesc material;  // name from newmtl; loc: the newmtl line
  std::optional<MtlTextureRef> diffuseMap;
};

struct MtlLibrary {
  std::vector<MtlMaterial> materials;  // in the order the file defines them
  // "file:line: what was skipped, and what is used instead", each kind once.
  std::vector<std::string> warnings;
};

// Parses the text of the MTL file at path. Throws SceneError at file:line:col for a number that
// is malformed, not finite or out of its range (negative colours, d outside [0, 1], ...).
MtlLibrary parseMtl(std::string_view text, const std::string& path);

}  // namespace prism
