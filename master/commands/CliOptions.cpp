#include "master/commands/CliOptions.h"

#include "util/MemorySize.h"

namespace prism {

void addImageSizeOptions(CLI::App* command, RenderOptions& o, const std::string& sppHelp) {
  addLimited(command, "-W,--width", o.width, limits::kWidth,
             "Image width in pixels (overrides the scene)");
  addLimited(command, "-H,--height", o.height, limits::kHeight,
             "Image height in pixels (overrides the scene)");
  addLimited(command, "-s,--spp", o.samples, limits::kSamples, sppHelp);
}

void addMemoryLimitOption(CLI::App* command, RenderOptions& o) {
  command
      ->add_option_function<std::string>(
          "--memory-limit",
          [&o](const std::string& text) { o.memoryLimit = parseMemorySize(text); },
          "Memory a run may plan to use, e.g. 512M, 8G, 1.5T (default: physical memory); "
          "larger requests are refused before anything is allocated, see docs/reliability.md")
      ->option_text("SIZE");
}

void addSceneArgument(CLI::App* command, RenderOptions& o) {
  command
      ->add_option("scene", o.scenePath,
                   "Scene file (.yaml, .yml or .nff), or a model file rendered as a scene (.obj, "
                   ".ply, .gltf, .glb)")
      ->required();
}

void addCausticMethodOptions(CLI::App* command, RenderOptions& o) {
  const char* caustics = kCausticsGroup;
  addNamed(command, "--caustics", o.causticMethod, kCausticMethodNames,
           "Caustics method: none, photon_map or caustic_map (or map; default: the scene's)")
      ->group(caustics);
  addLimited(command, "--photons", o.photons, limits::kPhotons,
             "Photons emitted per pass towards the caustic casters (implies photon_map)")
      ->group(caustics);
  addLimited(command, "--map-resolution", o.mapResolution, limits::kMapResolution,
             "Caustic map: texels per side of each light-space view (default 512)")
      ->group(caustics);
  addLimited(command, "--map-steps", o.mapSteps, limits::kMapSteps,
             "Caustic map: iterations of the receiver-distance estimate (default 10)")
      ->group(caustics);
  command
      ->add_option("--map-blur-sigma", o.mapBlurSigma,
                   "Caustic map: Gaussian blur sigma in texels (default 1)")
      ->check(CLI::NonNegativeNumber)
      ->group(caustics);
  addLimited(command, "--map-blur-radius", o.mapBlurRadius, limits::kMapBlurRadius,
             "Caustic map: Gaussian blur half-width in texels, 0: off (default 2)")
      ->group(caustics);
  addNamed(command, "--map-paths", o.mapPaths, kCausticMapPathsNames,
           "Caustic map: traced (through every caster surface, default) or front_face (one "
           "interface, as in the thesis)")
      ->group(caustics);
}

}  // namespace prism
