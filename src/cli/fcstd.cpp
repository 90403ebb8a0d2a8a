// `dispcon check|sweep|drag|assemble FILE.FCStd`: FreeCAD documents go to FreeCAD's freecadcmd,
// which runs the workbench's headless runner (freecad_workbench/dispcon_run.py). The arguments
// are parsed and checked here (bad usage is exit 2 before FreeCAD starts), handed over in a JSON
// file named in the environment (freecadcmd takes every argument for a document to open), and
// the runner's answer (exit code, standard output and error) comes back in another JSON file:
// freecadcmd's own exit code and output (a banner) say nothing about the study.
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"

namespace dispcon::cli {
namespace {

using nlohmann::json;

bool ends_with_fcstd(const std::string& s) {
  if (s.size() < 6) return false;
  std::string tail = s.substr(s.size() - 6);
  std::transform(tail.begin(), tail.end(), tail.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return tail == ".fcstd";
}

std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : fallback;
}

// freecadcmd: $DISPCON_FREECADCMD, else the first on PATH; empty when there is none.
std::string find_freecadcmd() {
  const std::string forced = env_or("DISPCON_FREECADCMD", "");
  if (!forced.empty()) return access(forced.c_str(), X_OK) == 0 ? forced : std::string();
  std::stringstream path(env_or("PATH", "/usr/bin:/bin"));
  std::string dir;
  while (std::getline(path, dir, ':')) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/freecadcmd";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

std::string temp_file(const char* tag) {
  std::string pattern = env_or("TMPDIR", "/tmp") + "/dispcon-" + tag + "-XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  const int fd = mkstemp(buf.data());
  if (fd < 0)
    throw std::runtime_error(std::string("cannot make a temporary file: ") + std::strerror(errno));
  close(fd);
  return buf.data();
}

// Runs freecadcmd on the runner with the request; returns the runner's exit code, or kBadInput
// with a message when FreeCAD could not give an answer.
int hand_to_freecad(json request) {
  const std::string& file = request["file"].get_ref<const std::string&>();
  const std::string freecadcmd = find_freecadcmd();
  if (freecadcmd.empty()) {
    std::cerr << file << ": error: FreeCAD is needed for .FCStd documents and its freecadcmd is "
              << "not on PATH (install FreeCAD 0.20 or later, or set DISPCON_FREECADCMD)\n";
    return kBadInput;
  }
  struct stat st {};
  if (stat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    std::cerr << file << ": error: no such file\n";
    return kBadInput;
  }
  const std::string workbench = env_or("DISPCON_FC_WORKBENCH", DISPCON_FC_WORKBENCH_DIR);
  const std::string runner = workbench + "/dispcon_run.py";
  const std::string request_path = temp_file("request"), result_path = temp_file("result");
  request["result"] = result_path;
  std::ofstream(request_path) << request.dump();
  std::cout.flush();
  const pid_t pid = fork();
  if (pid == 0) {
    setenv("DISPCON_FC_REQUEST", request_path.c_str(), 1);
    setenv("DISPCON_FC_WORKBENCH", workbench.c_str(), 1);
    setenv("DISPCON_PYTHONPATH", env_or("DISPCON_PYTHONPATH", DISPCON_PYTHON_MODULE_DIR).c_str(),
           1);
    // FreeCAD's banner and log on standard output would spoil the JSON: only stderr passes.
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, STDOUT_FILENO);
    execl(freecadcmd.c_str(), freecadcmd.c_str(), runner.c_str(), static_cast<char*>(nullptr));
    std::perror("freecadcmd");
    _exit(127);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) < 0) status = -1;
  std::ifstream in(result_path);
  json answer = json::parse(in, nullptr, /*allow_exceptions=*/false);
  std::remove(request_path.c_str());
  std::remove(result_path.c_str());
  if (answer.is_discarded() || !answer.contains("exit")) {
    std::cerr << file << ": error: " << freecadcmd << " ended (status " << status
              << ") without an answer from " << runner << "\n";
    return kBadInput;
  }
  std::cout << answer.value("stdout", "");
  std::cerr << answer.value("stderr", "");
  return answer["exit"].get<int>();
}

struct Args {
  std::string file, assembly, joint, body, csv, plot, svg, view = "iso", write;
  std::optional<double> from, to_value;
  std::vector<double> to, rotation;
  std::optional<double> tolerance;
  std::optional<int> max_iterations, steps;
  bool json = false, in_place = false, no_interference = false;
};

void add_document_options(CLI::App* sub, Args& a) {
  sub->add_option("FILE", a.file, "the FreeCAD document (.FCStd)")->required();
  sub->add_option("--assembly", a.assembly, "the assembly's Label, when the document has several");
  sub->add_option("--tolerance", a.tolerance,
                  "largest violation accepted (default: the assembly's)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--max-iterations", a.max_iterations, "iteration cap (default: the assembly's)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--json", a.json, "print one JSON document on standard output");
}

void add_picture_options(CLI::App* sub, Args& a) {
  sub->add_option("--svg", a.svg, "write an animated SVG of the parts moving, with the plot");
  sub->add_option("--view", a.view, "view plane of the animation: xy, xz, yz or iso (default)")
      ->check(CLI::IsMember({"xy", "xz", "yz", "iso"}));
}

void add_write_options(CLI::App* sub, Args& a) {
  sub->add_option("--write", a.write, "save the moved document as OUT.FCStd");
  sub->add_flag("--in-place", a.in_place, "save the moved document over the input");
}

json request_of(const std::string& command, const Args& a) {
  json r = {{"command", command}, {"file", a.file}, {"json", a.json}};
  if (!a.assembly.empty()) r["assembly"] = a.assembly;
  if (a.tolerance) r["tolerance"] = *a.tolerance;
  if (a.max_iterations) r["max_iterations"] = *a.max_iterations;
  if (a.steps) r["steps"] = *a.steps;
  auto put = [&](const char* key, const std::string& v) {
    if (!v.empty()) r[key] = v;
  };
  put("joint", a.joint);
  put("body", a.body);
  put("csv", a.csv);
  put("plot", a.plot);
  put("svg", a.svg);
  put("view", a.view);
  put("write", a.write);
  if (a.from) r["from"] = *a.from;
  if (command == "sweep" && a.to_value) r["to"] = *a.to_value;
  if (command == "drag") r["to"] = a.to;
  if (!a.rotation.empty()) r["rotation"] = a.rotation;
  r["in_place"] = a.in_place;
  r["no_interference"] = a.no_interference;
  return r;
}

}  // namespace

bool is_fcstd_call(int argc, char** argv) {
  bool fcstd = false;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() > 4 && arg.compare(arg.size() - 4, 4, ".dcl") == 0) return false;
    fcstd = fcstd || ends_with_fcstd(arg);
  }
  return argc > 1 && fcstd;
}

int run_fcstd(int argc, char** argv) {
  CLI::App app{"dispcon on FreeCAD documents: checks, sweeps and drags of their assemblies"};
  app.require_subcommand(1);
  Args a;
  CLI::App* check = app.add_subcommand("check",
                                       "does it assemble, degrees of freedom, "
                                       "redundant and conflicting joints, overlaps");
  add_document_options(check, a);
  check->add_flag("--no-interference", a.no_interference, "do not test the parts for overlaps");
  CLI::App* sweep = app.add_subcommand("sweep",
                                       "drive a joint through a range: lock-ups, "
                                       "limits, joint values, interference");
  add_document_options(sweep, a);
  sweep->add_option("--joint", a.joint, "the Label of the joint to drive (revolute or slider)")
      ->required();
  sweep->add_option("--from", a.from, "start value (radians or length; default: where it is)");
  sweep->add_option("--to", a.to_value, "end value (default: a full turn further)");
  sweep->add_option("--steps", a.steps, "number of steps (default 360)")
      ->check(CLI::PositiveNumber);
  sweep->add_option("--csv", a.csv, "write every sample");
  sweep->add_option("--plot", a.plot, "write an SVG plot of every joint's value");
  sweep->add_flag("--no-interference", a.no_interference, "do not test the parts for collisions");
  add_picture_options(sweep, a);
  CLI::App* drag = app.add_subcommand("drag", "move a part to a pose while the rest follows");
  add_document_options(drag, a);
  drag->add_option("--body", a.body, "the Label of the part to move")->required();
  drag->add_option("--to", a.to, "target position X Y Z")->expected(3)->required();
  drag->add_option("--rotation", a.rotation, "target rotation vector RX RY RZ (radians)")
      ->expected(3);
  drag->add_option("--steps", a.steps, "number of steps (default 50)")->check(CLI::PositiveNumber);
  drag->add_option("--csv", a.csv, "write every step's poses");
  add_picture_options(drag, a);
  add_write_options(drag, a);
  CLI::App* assemble = app.add_subcommand("assemble", "snap the parts into place");
  add_document_options(assemble, a);
  add_write_options(assemble, a);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kBadInput;
  }
  for (CLI::App* sub : {check, sweep, drag, assemble}) {
    if (sub->parsed()) {
      try {
        return hand_to_freecad(request_of(sub->get_name(), a));
      } catch (const std::exception& e) {
        std::cerr << a.file << ": error: " << e.what() << "\n";
        return kBadInput;
      }
    }
  }
  return kBadInput;
}

}  // namespace dispcon::cli
