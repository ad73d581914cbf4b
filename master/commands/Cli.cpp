#include "master/commands/Cli.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "master/commands/CliOptions.h"
#include "master/commands/RenderCommand.h"
#include "master/commands/SpeedupCommand.h"
#include "master/commands/SweepCli.h"
#include "master/commands/SweepCommand.h"
#include "master/commands/ViewerCli.h"
#include "master/dispatch/GeometryShare.h"
#include "master/dispatch/ScheduleNames.h"
#include "scene/SettingLimits.h"
#include "scene/SettingNames.h"
#include "util/InstructionSet.h"
#include "util/MemorySize.h"

namespace prism {
namespace {

constexpr const char* kVersion = "0.1.0";

// The options `render` and `view` share: scene, overrides, threads and distribution.
void addSceneOptions(CLI::App* render, RenderOptions& o) {
  addSceneArgument(render, o);
  render
      ->add_option("-t,--threads", o.distribution.threads,
                   "Worker threads (default 0: all available cores)")
      ->check(CLI::Range(0, 4096));
  addImageSizeOptions(render, o, "Samples per pixel, stratified (overrides the scene)");
  addLimited(render, "-d,--max-depth", o.maxDepth, limits::kMaxDepth,
             "Maximum reflection/refraction depth");
  render->add_option("--seed", o.seed, "Seed of the per-pixel random streams");
  render->add_option("--exposure", o.exposure, "Radiance multiplier before PNG tone mapping")
      ->check(CLI::PositiveNumber);
  const auto addPoint = [render](const std::string& flags, std::optional<Vec3>* target,
                                 const std::string& help) {
    render
        ->add_option_function<std::string>(
            flags, [target](const std::string& text) { *target = parseVec3(text); }, help)
        ->option_text("X,Y,Z");
  };
  addPoint("--camera-position", &o.cameraPosition, "Camera position X,Y,Z (overrides the scene)");
  addPoint("--look-at", &o.lookAt,
           "Camera look-at point X,Y,Z (overrides the scene; the viewer prints both for the view "
           "it saves)");
  addNamed(render, "--triangle-test", o.triangleTest, kTriangleTestNames,
           "Ray/triangle intersector: moller_trumbore (default), plane_inside or watertight");
  render
      ->add_option_function<std::string>(
          "--isa",
          [&o](const std::string& text) {
            const std::optional<InstructionSet> isa = parseInstructionSet(text);
            if (!isa) {
              throw CLI::ValidationError("--isa", "unknown instruction set '" + text +
                                                      "' (expected auto, x86-64, v2, v3 or v4)");
            }
            o.instructionSet = *isa;
          },
          "Instruction set of the ray kernels on every rank: auto (default: the best every rank "
          "runs), x86-64 (the baseline, SSE2), v2, v3 (AVX2) or v4 (AVX-512); refused where a "
          "rank's CPU lacks it. The run summary says which ran (docs/performance.md)")
      ->option_text("auto|x86-64|v2|v3|v4");
  render
      ->add_option("--tile-size", o.distribution.tileSize,
                   "Tile edge in pixels (default 0: automatic)")
      ->check(CLI::Range(0, 4096));
  addNamed(render, "--schedule", o.distribution.schedule, kScheduleNames,
           "MPI tile schedule: dynamic (pull queue, default) or static (interleaved)");
  render
      ->add_option("--lease-timeout", o.distribution.leaseSeconds,
                   "Seconds a slave may hold tiles without delivering one before they are "
                   "re-issued and it is retired (default 30)")
      ->check(CLI::Range(0.1, 86400.0));
  render
      ->add_option("--heartbeat-timeout", o.distribution.heartbeatTimeoutSeconds,
                   "Seconds of silence after which a slave is taken for dead and its tiles "
                   "re-issued; slaves heartbeat twice a second (default 2)")
      ->check(CLI::Range(0.6, 86400.0));
  render
      ->add_option("--prefetch", o.distribution.prefetch,
                   "Tiles in flight per slave render thread (default 2)")
      ->check(CLI::Range(1, 64));
  render
      ->add_option_function<std::string>(
          "--bvh-share",
          [&o](const std::string& text) {
            try {
              o.geometryShare = parseGeometryShareMode(text);
            } catch (const std::invalid_argument& e) {
              throw CLI::ValidationError("--bvh-share", e.what());
            }
          },
          "MPI runs: auto (default: rank 0 broadcasts the BVH it built where the link measured "
          "at the start moves it faster than the slaves would build it), broadcast, or local "
          "(every rank builds its own); the same pixels either way (docs/distributed.md)")
      ->option_text("auto|broadcast|local");
  addMemoryLimitOption(render, o);
  render->add_flag(
      "--overwrite", o.overwrite,
      "Replace an existing image file (a finished frame is never replaced without it)");
  // Testing only, so not in --help: makes one slave misbehave.
  render
      ->add_option_function<std::string>(
          "--inject-fault",
          [&o](const std::string& text) { o.distribution.fault = parseFaultInjection(text); }, "")
      ->group("");
}

// The caustics options of `render` only: the viewer always refines progressively, with the
// scene's gather settings.
void addCausticOptions(CLI::App* render, RenderOptions& o) {
  const char* caustics = kCausticsGroup;
  addCausticMethodOptions(render, o);
  CLI::Option* gather = addLimited(render, "--gather", o.gather, limits::kGather,
                                   "Nearest photons per estimate, k (default 100). Larger k "
                                   "smooths a caustic's regular part (800: about POV-Ray's best "
                                   "there, for about twice the time); smaller k with more "
                                   "--photons sharpens folds (docs/caustics.md, levers)");
  gather->group(caustics);
  render
      ->add_option("--gather-noise", o.gatherNoise,
                   "Automatic k (the scene's gather: auto): each photon's own k, up to "
                   "1/noise^2 where the photon density is smooth, fewer at folds and foci; "
                   "e.g. 0.05 (k up to 400)")
      ->check(CLI::Range(limits::kSmallestGatherNoise, 1.0f))
      ->excludes(gather)
      ->group(caustics);
  render
      ->add_option("--gather-radius", o.gatherRadius,
                   "Largest gather radius (k-NN), or the first radius (progressive); world units")
      ->check(CLI::PositiveNumber)
      ->group(caustics);
  render
      ->add_flag_callback(
          "--progressive", [&o] { o.progressive = true; },
          "Progressive photon mapping: passes with a shrinking radius (implies photon_map)")
      ->group(caustics);
  addLimited(render, "--passes", o.passes, limits::kPasses,
             "Progressive photon passes (implies photon_map)")
      ->group(caustics);
  render
      ->add_option(
          "--time-budget", o.timeBudget,
          "Seconds for the whole run, start to written image: progressive photon passes "
          "(implies --progressive) until the budget ends, or --passes if given; a pass starts "
          "only if it (as long as the longest so far) and the write fit (the first always runs)")
      ->check(CLI::PositiveNumber)
      ->group(caustics);
  render
      ->add_option("--photon-image", o.photonImagePath,
                   "Debug: also write an image of where the stored photons landed")
      ->group(caustics);
  render
      ->add_option("--caustic-map-debug", o.causticMapDebugPrefix,
                   "Debug: write the caustic maps as PREFIX-light<i>-<map>.png (receiver "
                   "positions, caster positions and normals, caustic irradiance)")
      ->group(caustics);
}

void addRenderCommand(CLI::App& app, RenderOptions& o) {
  CLI::App* render = app.add_subcommand(
      "render",
      "Render a scene to an image file.\n"
      "Scenes: Prism YAML (.yaml/.yml, see docs/scene-format.md) or NFF (.nff).\n"
      "Images: .png (tone-mapped sRGB) or .exr (linear radiance), by extension.");
  addSceneOptions(render, o);
  render->add_option("-o,--output", o.outputPath,
                     "Image to write; the extension picks the format (default: <scene>.png)");
  render->add_flag("-q,--quiet", o.quiet, "No progress bar and no summary");
  render->add_option("--status-file", o.statusFile, "")->group("");  // tests: tiles done so far
  render->add_flag("--save-partial", o.savePartial,
                   "On Ctrl-C (SIGINT/SIGTERM) write the finished tiles to <output>.partial.<ext>, "
                   "marked partial; the run exits with status 130 either way");
  addCausticOptions(render, o);
}

void addViewCommand(CLI::App& app, ViewOptions& o) {
  CLI::App* view = app.add_subcommand(
      "view",
      "Render a scene live in a Qt window (rank 0 only; other ranks render tiles), or serve\n"
      "it (--serve) to `prism connect` on another machine.\n"
      "Keys: W/A/S/D move, Q/E down/up, arrows rotate, drag orbits, wheel zooms, r resets,\n"
      "N normals, n image, R/P/C caustic-map casters/receivers/irradiance, b caustic-map\n"
      "blur, q quits, h or F1 shows every key. See docs/viewer.md.");
  addSceneOptions(view, o.render);
  addCausticMethodOptions(view, o.render);
  view->add_option("--preview-scale", o.previewScale,
                   "While the camera moves, frames may drop to 3/4, 2/3, 1/2, 1/3, ... down to "
                   "1/N of each side to meet --frame-time (default 4; 1: always full resolution)")
      ->check(CLI::Range(1, 64));
  view->add_option("--frame-time", o.frameTimeMilliseconds,
                   "Target time of a frame while the camera moves, in ms (default 33.3: 30 "
                   "frames/s); the resolution drops only when a frame would miss it. 0: no "
                   "target, always full resolution")
      ->check(CLI::Range(0.0, 60000.0));
  view->add_flag_callback(
      "--no-pipeline", [&o] { o.pipeline = false; },
      "Hand out a frame's tiles only once the frame before is complete (to measure what "
      "pipelining gains)");
  view->add_option("--max-passes", o.maxPasses,
                   "Full-resolution passes of --spp samples averaged while the camera is still "
                   "(default 64)")
      ->check(CLI::Range(1, 1 << 20));
  addViewerWindowOptions(view, o.window);
  addServeOptions(view, o.serve);
}

void addSpeedupCommand(CLI::App& app, SpeedupOptions& o) {
  CLI::App* speedup = app.add_subcommand(
      "speedup",
      "Measure strong scaling inside one MPI job (table, CSVs, charts).\n"
      "The same frame is rendered by 1..N-1 slaves (rank 0 coordinates, the other slaves idle)\n"
      "and by 1 process on 1 thread (T1, no MPI).\n"
      "Every point is repeated; set-up (parse, broadcast, scene build, photon pass) is timed\n"
      "apart. Prints speedup, efficiency, Karp-Flatt serial fraction, per-slave busy time and an\n"
      "Amdahl fit; writes PREFIX.csv, PREFIX-projection.csv, PREFIX-speedup.png and\n"
      "PREFIX-projection.png (charts need Qt). The projection simulates the tile queue with\n"
      "the measured tile costs and link for up to --project-workers workers and images up to\n"
      "8K, validated on the measured points. Start it as: mpiexec -n N prism speedup SCENE\n"
      "(--oversubscribe when N exceeds the cores). See docs/scaling.md.");
  addSceneArgument(speedup, o.render);
  speedup->add_option("-o,--output", o.outputPrefix,
                      "Prefix of the files written (default: speedup-<scene name>)");
  addNamed(speedup, "--schedules", o.schedules, kScheduleNames,
           "Tile schedules to measure, comma-separated (default: dynamic,static)")
      ->delimiter(',')
      ->option_text("dynamic,static");
  speedup
      ->add_option("--tile-sizes", o.tileSizes,
                   "Tile edges to sweep, comma-separated (default: the automatic size for N-1 "
                   "slaves)")
      ->delimiter(',')
      ->check(CLI::Range(4, 4096));
  speedup
      ->add_option("--threads-per-rank", o.threadsPerRank,
                   "Render threads of each slave (default 1); p counts slaves x threads")
      ->check(CLI::Range(1, 4096));
  speedup
      ->add_option("-r,--repeats", o.repeats,
                   "Runs of every point; medians are reported "
                   "with min and max (default 5)")
      ->check(CLI::Range(1, 1000));
  speedup
      ->add_option("--prefetch", o.render.distribution.prefetch,
                   "Tiles in flight per slave render thread (default 2)")
      ->check(CLI::Range(1, 64));
  speedup
      ->add_option("--project-workers", o.projectWorkers,
                   "Largest worker count of the projection (default 1024)")
      ->check(CLI::Range(1, 1 << 16));
  addImageSizeOptions(speedup, o.render, "Samples per pixel (overrides the scene)");
  addCausticMethodOptions(speedup, o.render);
  addMemoryLimitOption(speedup, o.render);
  speedup->add_flag("-q,--quiet", o.quiet, "No progress bar");
}

// `prism` alone: the commands, one line each (the first line of each one's help), and where
// to read more.
void printCommandList(const CLI::App& app, std::ostream& out) {
  out << app.get_description() << "\n\nUsage: prism <command> [options]\n\nCommands:\n";
  for (const CLI::App* command : app.get_subcommands({})) {
    const std::string& help = command->get_description();
    out << "  " << command->get_name() << std::string(10 - command->get_name().size(), ' ')
        << help.substr(0, help.find('\n')) << "\n";
  }
  out << "\nRun 'prism <command> --help' for a command's options, 'prism --version' for the "
         "version.\nDocumentation: README.md and docs/ (scene format: docs/scene-format.md).\n";
}

}  // namespace

ParsedCommand parseCommandLine(int argc, char** argv, bool quiet, const ViewerRunner& viewer,
                               const ChartWriter& chartWriter) {
  CLI::App app{"Prism: a distributed ray tracer with photon-mapped caustics."};
  app.set_version_flag("-V,--version", std::string("prism ") + kVersion);
  app.require_subcommand(1);
  app.footer("Run 'prism <command> --help' for a command's options.");

  // Kept alive by the command's closure: CLI11 writes into them while parsing.
  auto renderOptions = std::make_shared<RenderOptions>();
  auto viewOptions = std::make_shared<ViewOptions>();
  auto speedupOptions = std::make_shared<SpeedupOptions>();
  auto sweepOptions = std::make_shared<SweepOptions>();
  auto connectOptions = std::make_shared<ConnectCommandOptions>();
  addRenderCommand(app, *renderOptions);
  addViewCommand(app, *viewOptions);
  addConnectCommand(app, *connectOptions);
  addSpeedupCommand(app, *speedupOptions);
  addSweepCommand(app, *sweepOptions);

  ParsedCommand parsed;
  if (argc <= 1) {
    if (!quiet) printCommandList(app, std::cout);
    parsed.exitNow = true;
    return parsed;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    parsed.exitNow = true;
    parsed.exitCode = quiet ? e.get_exit_code() : app.exit(e);
    return parsed;
  } catch (const std::invalid_argument& e) {
    if (!quiet) std::cerr << "prism: error: " << e.what() << "\n";
    parsed.exitNow = true;
    parsed.exitCode = 1;
    return parsed;
  }

  if (app.get_subcommand("render")->parsed()) {
    parsed.distribution = renderOptions->distribution;
    parsed.memoryLimit = renderOptions->memoryLimit;
    parsed.runMaster = [renderOptions](Transport* session) {
      return runRender(*renderOptions, std::cout, std::cerr, session);
    };
  } else if (app.get_subcommand("view")->parsed()) {
    parsed.distribution = viewOptions->render.distribution;
    parsed.memoryLimit = viewOptions->render.memoryLimit;
    parsed.runMaster = [viewOptions, viewer](Transport* session) {
      return runView(*viewOptions, std::cout, std::cerr, session, viewer);
    };
  } else if (app.get_subcommand("connect")->parsed()) {
    parsed.runMaster = [connectOptions, viewer](Transport* session) {
      return runConnect(*connectOptions, std::cout, std::cerr, session, viewer);
    };
  } else if (app.get_subcommand("speedup")->parsed()) {
    parsed.distribution = speedupOptions->render.distribution;
    parsed.memoryLimit = speedupOptions->render.memoryLimit;
    parsed.distribution.threads = speedupOptions->threadsPerRank;  // what p counts
    parsed.runMaster = [speedupOptions, chartWriter](Transport* session) {
      return runSpeedup(*speedupOptions, std::cout, std::cerr, session, chartWriter);
    };
  } else if (app.get_subcommand("sweep")->parsed()) {
    parsed.distribution = sweepOptions->render.distribution;
    parsed.memoryLimit = sweepOptions->render.memoryLimit;
    parsed.runMaster = [sweepOptions, chartWriter](Transport* session) {
      return runSweep(*sweepOptions, std::cout, std::cerr, session, chartWriter);
    };
  } else {
    parsed.exitNow = true;
    parsed.exitCode = 1;
  }
  return parsed;
}

}  // namespace prism
