// valve-render MESH.vtp --out DIR [--array NAME] [--range MIN,MAX] [--views top,side]
//              [--axis z] [--title TEXT] [--size PIXELS] [--quiet]
// Writes DIR/<mesh stem>_<view>.png and DIR/render.summary.json. Without an X display the
// stage re-runs itself under xvfb-run; where that is impossible it warns, writes a summary
// with status "skipped" and exits 0 (pictures are for people, never a reason to fail a
// pipeline).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "valve/core/cli.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/core/error.hpp"
#include "valve/io/render.hpp"
#include "valve/pipeline/process.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream ss(s);
  for (std::string p; std::getline(ss, p, sep);)
    if (!p.empty()) parts.push_back(p);
  return parts;
}

}  // namespace

int main(int argc, char** argv) {
  // Debian's VTK needs X: give ourselves a virtual display once, before anything is written.
  if (!render_display_available() && !std::getenv("VALVE_RENDER_UNDER_XVFB") && find_on_path("xvfb-run")) {
    setenv("VALVE_RENDER_UNDER_XVFB", "1", 1);
    std::vector<char*> args{const_cast<char*>("xvfb-run"), const_cast<char*>("-a"), const_cast<char*>("-s"),
                            const_cast<char*>("-screen 0 1280x1024x24")};
    for (int i = 0; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    execvp("xvfb-run", args.data());  // returns only on failure: fall through to the skip path
  }
  return run_stage("valve-render", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"out", "array", "range", "views", "axis", "title", "size"}, {"quiet"});
    if (cl.positional().size() != 1)
      throw InputError("valve-render: expected one MESH.vtp argument, found " + std::to_string(cl.positional().size()));
    const fs::path mesh_file = cl.positional()[0];
    const fs::path out = cl.require("out");
    StageArguments args(cl, {});
    RenderOptions opt;
    opt.array = cl.get("array").value_or("");
    if (const auto range = args.numbers("range", 2)) {
      opt.range_min = (*range)[0];
      opt.range_max = (*range)[1];
      if (!(opt.range_max > opt.range_min)) throw InputError("valve-render: --range: expected MIN < MAX, found \"" + *cl.get("range") + "\"");
    }
    if (auto v = cl.get("views")) opt.views = split(*v, ',');
    opt.axis = cl.get("axis").value_or("z");
    opt.title = cl.get("title").value_or("");
    opt.width = opt.height = static_cast<int>(args.integer("size", opt.width, 64, 8192));
    StageSummary summary("render", out);
    summary.add_input("mesh", mesh_file);
    summary.parameters() = {{"array", opt.array}, {"views", opt.views}, {"axis", opt.axis}, {"size", opt.width}};
    if (!render_display_available()) {
      const std::string reason = "no X display and no xvfb-run: install xvfb to get pictures";
      std::fprintf(stderr, "valve-render: warning: skipped: %s\n", reason.c_str());
      summary.set_status("skipped", reason);
      summary.write();
      return 0;
    }
    const auto files = render_views(mesh_file, opt, out, mesh_file.stem().string());
    nlohmann::json list = nlohmann::json::array();
    for (const auto& f : files) list.push_back(f.filename().string());
    summary.metrics()["images"] = list;
    summary.write();
    if (!cl.has("quiet"))
      for (const auto& f : files) std::printf("valve-render: wrote %s\n", f.string().c_str());
    return 0;
  });
}
