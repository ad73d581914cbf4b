#include "master/commands/SweepCli.h"

#include <CLI/CLI.hpp>

#include "master/commands/CliOptions.h"

namespace prism {

void addSweepCommand(CLI::App& app, SweepOptions& o) {
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "Chart speed against accuracy of the caustic methods (CSV, chart).\n"
      "Renders the scene with each caustic method over a range of budgets, times every point\n"
      "(median of --repeats runs, taken in rounds) and scores it\n"
      "against a reference: RMSE, relative RMSE, MRSE, max error and caustic flux ratio, over\n"
      "the whole frame and the caustic region. Families (--families):\n"
      "  photons     photon map: photons per pass     k           photon map: photons gathered\n"
      "  autok       photon map, automatic k: its largest k (the target noise 1/sqrt(k))\n"
      "  passes      progressive photon map: passes   resolution  caustic map: texels per side\n"
      "  steps       caustic map: distance iterations blur        caustic map: blur half-width\n"
      "  spp         samples per pixel, with the scene's own method\n"
      "Reference (--reference): analytic for scenes whose casters are flat mirrors in one plane\n"
      "(scenes/caustic-mirror.yaml), else progressive photon mapping at a high budget, cached\n"
      "as PREFIX-reference.exr/.csv, or an image file. Writes PREFIX.csv and the chart\n"
      "PREFIX.png (error against time, log-log, Pareto front, thumbnails; needs Qt).\n"
      "One process; see docs/accuracy.md.");
  addSceneArgument(sweep, o.render);
  sweep->add_option("-o,--output", o.outputPrefix,
                    "Prefix of the files written (default: sweep-<scene name>)");
  addNamed(sweep, "--families", o.families, kSweepFamilyNames,
           "Families to sweep, comma-separated (default: photons,k,passes,resolution,steps,blur)")
      ->delimiter(',')
      ->option_text(kSweepFamilyNames.list(",", ","));
  const char* values = "Values swept (comma-separated; each overrides its family's defaults)";
  const auto list = [&](const char* name, std::vector<uint64_t>& target, const char* help) {
    sweep->add_option(name, target, help)->delimiter(',')->group(values);
  };
  list("--photons-list", o.values.photons,
       "photons (default 25000,50000,100000,200000,400000,800000,1600000)");
  list("--k-list", o.values.gather, "k (default 10,25,50,100,200,400)");
  list("--autok-list", o.values.autoGather,
       "largest k of the automatic k (default 25,100,400,1600)");
  list("--passes-list", o.values.passes, "passes (default 1,2,4,8,16,32)");
  list("--resolution-list", o.values.resolution, "resolution (default 64,128,256,512,1024)");
  list("--steps-list", o.values.steps, "steps (default 1,2,3,5,10,20)");
  list("--blur-list", o.values.blur, "blur half-width, sigma = half (default 0,1,2,4,8)");
  list("--spp-list", o.values.samples, "spp (default 1,2,4,8,16)");
  sweep->add_option("-r,--repeats", o.repeats, "Timed runs of every point; medians (default 3)")
      ->check(CLI::Range(1, 1000));
  addMemoryLimitOption(sweep, o.render);
  sweep
      ->add_option("--reference", o.reference.spec,
                   "auto (default: analytic when the scene allows it, else progressive), "
                   "analytic, progressive, or an image file (.exr) of the same size")
      ->option_text("auto|analytic|progressive|FILE");
  sweep
      ->add_option("--reference-passes", o.reference.passes,
                   "Progressive reference: passes (default 64)")
      ->check(CLI::Range(int64_t{2}, limits::kPasses.max));
  sweep
      ->add_option("--reference-photons", o.reference.photons,
                   "Progressive reference: photons per pass (default 1000000)")
      ->check(CLI::Range(limits::kPhotons.min, limits::kPhotons.max));
  sweep
      ->add_option("--reference-k", o.reference.k,
                   "Progressive reference: the k of its per-photon k-NN radii (default 5)")
      ->check(CLI::Range(limits::kGather.min, limits::kGather.max));
  sweep->add_flag("--refresh-reference", o.reference.refresh,
                  "Render the progressive reference again even when the cached one matches");
  sweep
      ->add_option("--budget-seconds", o.budgetSeconds,
                   "Start no timed run after this many seconds of sweeping (the reference not "
                   "counted); the chart says how many points were measured")
      ->check(CLI::PositiveNumber);
  sweep
      ->add_option_function<std::string>(
          "--time-axis", [&o](const std::string& axis) { o.cpuAxis = axis == "cpu"; },
          "Time charted: wall (default) or cpu seconds of the process")
      ->check(CLI::IsMember({"wall", "cpu"}));
  sweep
      ->add_option("--thumbnail-height", o.thumbnailHeight,
                   "Height of the chart's thumbnails in pixels (default 96)")
      ->check(CLI::Range(16, 1024));
  sweep
      ->add_option("-t,--threads", o.render.distribution.threads,
                   "Render threads (default 0: all available cores)")
      ->check(CLI::Range(0, 4096));
  addImageSizeOptions(sweep, o.render, "Samples per pixel (overrides the scene)");
  addCausticMethodOptions(sweep, o.render);
  sweep->add_flag("-q,--quiet", o.quiet, "No progress bar and no table");
}

}  // namespace prism
