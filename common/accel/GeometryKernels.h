// The geometry kernels of one instruction set: where SceneGeometry's calls go. Each set's
// kernels are the same sources compiled for it as whole translation units (CMakeLists.txt,
// "Kernels per instruction set"), so code the compiler inlines into them is compiled for that
// set too; their symbols are made private to the set's object, so no inline function compiled
// for AVX-512 can stand in for the baseline's copy elsewhere in the program.
#pragma once

#include "util/InstructionSet.h"

namespace prism {

class SceneGeometry;
struct Ray;
struct HitRecord;
struct SurfaceHit;

struct GeometryKernels {
  InstructionSet instructionSet;
  int packetLanes;  // rays one vector of a packet test holds: 8 with AVX2, else 4
  bool (*intersect)(const SceneGeometry&, const Ray&, HitRecord&);
  bool (*occluded)(const SceneGeometry&, const Ray&);
  void (*intersect8)(const SceneGeometry&, const Ray*, int, HitRecord*, bool*);
  void (*occluded8)(const SceneGeometry&, const Ray*, int, bool*);
  void (*surface)(const SceneGeometry&, const Ray&, const HitRecord&, SurfaceHit&);
};

// The kernels compiled for isa, which must be a concrete set this binary holds (Baseline
// always; the others where runnableInstructionSets() says so).
const GeometryKernels& geometryKernels(InstructionSet isa);

}  // namespace prism
