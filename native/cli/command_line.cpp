// probelights: the command-line tool, thin over the library: the usage and the dispatch to one file per
// command (bake_command.cpp, sh_commands.cpp, tradeoff_command.cpp; their options in options.h). Exit codes:
// 0 success, 2 bad input or request (one line on stderr), 1 an unexpected internal failure. Run by main.cpp's
// program and, in the Python package, by its module in the `probelights` entry point's process (python/).
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bake_args.h"
#include "commands.h"
#include "options.h"
#include "write_whole.h"

namespace {

using namespace probelights;
using namespace probelights::cli;

const char* kUsage =
    R"(usage: probelights bake PROBE [options]      N lights that carry exactly the probe's energy
       probelights bake PROBE... --out-dir DIR [options]   a whole library, one JSON per probe
       probelights sh PROBE --bands B [options (sh)] [-o sh.json]
       probelights sample PROBE --bands B [options (sample)] [-o samples.json]
       probelights tradeoff PROBE [options (tradeoff)] [-o tradeoff.json] [--plot tradeoff.png]
       probelights evaluate PROBE LIGHTS.json [options (evaluate)] [-o errors.json]
       probelights bake-sequence 'sky_####.exr' [options (bake-sequence)] [-o lights.json]

PROBE is any image OpenImageIO reads. sh: real SH coefficients (Sloan order, orthonormal, Condon-Shortley
phase, theta from +Z) of the radiance, or with --irradiance of the irradiance. sample: directions and pdfs
from the SH importance sampler (Jarosz et al. 2009 warping with Berger's epsilon clamping) of the probe's
luminance. evaluate: the errors of any lights (a bake's JSON, or anybody's in its layout) against the probe.
bake-sequence: the frames of an animated world (#### the frame number, as Blender names a sequence) in the
same N lights every frame, each light keeping its "id" from frame to frame.

options (bake):
)";

// The command's own options, after the bake's (bakeOptionsUsage: the table the module shares).
const char* kUsageOwn =
    R"(  --both-cuts                       --cuts both
  --projection auto|latlong|mirror-ball|angular
                                    how the image maps to the sphere (default auto: lat-long for 2:1 images)
  -o, --output FILE                 write the lights as JSON ('-' for standard output)
  --preview FILE                    write a picture of the regions and lights (PNG)
  --residual FILE                   lamps for the probe's bright sources alone; write what the world keeps
                                    (the residual) to FILE (.exr): lamps + residual = the probe, exactly
                                    (--source-level, default 10 x the mean luminance, or --source-share)
)";

// A library bake's options, and the tradeoff's head.
const char* kUsageLibrary =
    R"(  --out-dir DIR                     bake many probes (files, folders, quoted globs) into DIR: a JSON
                                    each and summary.json; the next loads while one bakes; exit 3 if some
                                    failed
  --previews                        with --out-dir: a preview PNG per probe too
  -q, --quiet                       no summary on standard output

options (tradeoff): the grid, and how each row is made and judged, by the bake's options
)";

std::string usage() {
  return std::string(kUsage) + bakeOptionsUsage() + kUsageOwn + exportOptionsUsage() + kUsageLibrary +
         tradeoffOptionsUsage() +
         "  (and --projection, -o, --plot)\n\noptions (evaluate): how the lights are judged, by the bake's "
         "options\n" +
         evaluateOptionsUsage() + "  (and --projection, -o)\n\noptions (sh)\n" + shOptionsUsage() +
         "\noptions (sample)\n" + sampleOptionsUsage() +
         "  (sh, sample: and --projection; JSON goes to -o FILE or standard output)\n\noptions "
         "(bake-sequence)\n" +
         sequenceOptionsUsage() + "  (and --projection, -o)\n";
}

}  // namespace

int probelights::cli::run(const std::vector<std::string>& args) {
  quietLibraries();
  removeTemporariesOnSignal();  // Ctrl-C during a write leaves no temporary file (a library bake asks more)
  try {
    if (!args.empty() && args[0] == "--version") {
      std::puts("probelights " PROBELIGHTS_VERSION);
      return 0;
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::fputs(usage().c_str(), args.empty() ? messages() : stdout);
      return args.empty() ? 2 : 0;
    }
    const std::map<std::string, int (*)(const std::vector<std::string>&)> commands{
        {"bake", bakeCommand},         {"sh", shCommand},
        {"sample", sampleCommand},     {"tradeoff", tradeoffCommand},
        {"evaluate", evaluateCommand}, {"bake-sequence", sequenceCommand}};
    if (auto command = commands.find(args[0]); command != commands.end()) {
      std::vector<std::string> rest(args.begin() + 1, args.end());
      for (const auto& s : rest)
        if (s == "--help" || s == "-h") return std::fputs(usage().c_str(), stdout), 0;
      const int code = command->second(rest);
      writeStdout("");  // what is still buffered: a full disk or closed pipe behind stdout is an error
      return code;
    }
    throw UsageError("unknown command '" + args[0] +
                     "': use bake, bake-sequence, sh, sample, tradeoff or evaluate (see probelights --help)");
  } catch (const Error& e) {
    std::fprintf(messages(), "probelights: error: %s\n", described(e).c_str());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(messages(), "probelights: error: out of memory\n");
    return 2;
  } catch (const std::length_error&) {
    std::fprintf(messages(),
                 "probelights: error: out of memory (the request is larger than memory can be)\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(messages(), "probelights: internal error: %s\n", e.what());
    return 1;
  }
}
