// The CLI against hostile files and values (issue "Reliability"): a failed
// write never damages OUT (not even when OUT is IN), inputs that are not
// regular files or whose headers promise more than their bytes are refused at
// once, and every option value goes through the one strict number grammar.
#include <sys/stat.h>

#include <cerrno>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "anisoform/file_io.h"
#include "anisoform/mesh_io.h"
#include "cli_runner.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using aniso::test::CliRun;
using aniso::test::contains;
using aniso::test::describe;
using aniso::test::mesh_path;
using aniso::test::run_expecting;
using aniso::test::slurp;
using aniso::test::stdout_json;
using aniso::test::temp_path;

// A directory of its own (so that a temporary file left behind would show),
// removed with its content at the end of the test.
class CliScratch {
 public:
  explicit CliScratch(const std::string& name) : path_(temp_path(name)) { fs::create_directories(path_); }
  ~CliScratch() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  std::string copy_of_mesh(const std::string& relative, const std::string& name) const {
    aniso::write_file_atomically(file(name), slurp(mesh_path(relative)));
    return file(name);
  }
  std::size_t entry_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(path_), fs::directory_iterator()));
  }

 private:
  std::string path_;
};

// A file-size limit as a user's shell sets one, SIGXFSZ left at its default
// (the CLI ignores it itself, so that writing past the limit fails with
// EFBIG instead of killing it); `blocks` in the shell's ulimit units (512 or
// 1024 bytes).
const std::string kFileSizeLimit = "trap - XFSZ; ulimit -f ";

CliRun run_under_file_size_limit(int blocks, const std::vector<std::string>& args) {
  const CliRun run = aniso::test::run_cli_after_shell(kFileSizeLimit + std::to_string(blocks), args);
  INFO(describe(args, run));
  // Not killed by SIGXFSZ.
  REQUIRE_FALSE(run.signaled);
  REQUIRE_FALSE(run.timed_out);
  return run;
}

// The largest coordinate difference between two meshes' vertices.
double max_position_difference(const std::string& a, const std::string& b) {
  const aniso::Mesh first = aniso::read_mesh(a).mesh;
  const aniso::Mesh second = aniso::read_mesh(b).mesh;
  REQUIRE(first.V.rows() == second.V.rows());
  return (first.V - second.V).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("cli robustness: a write cut short by a file-size limit leaves OUT as it was", "[cli][robustness]") {
  CliScratch dir("write_limit");
  const std::string out = dir.copy_of_mesh("formats/spot_lowres.off", "out.off");
  const std::string before = slurp(out);
  const CliRun run = run_under_file_size_limit(
      8, {"deform", mesh_path("formats/spot_lowres.obj"), out, "--method", "andefgrad", "--scale", "1.3"});
  CHECK(run.exit_status == 3);
  CHECK(contains(run.err, "could not write " + out + ": File too large"));
  CHECK(run.out.empty());
  CHECK(slurp(out) == before);      // byte for byte
  CHECK(dir.entry_count() == 1);    // no temporary file left

  SECTION("flatten's patterns too") {
    const std::string svg = dir.file("pattern.svg");
    aniso::write_file_atomically(svg, "<svg>an older pattern</svg>\n");
    const CliRun flat = run_under_file_size_limit(1, {"flatten", mesh_path("open/plane.off"), svg});
    CHECK(flat.exit_status == 3);
    CHECK(contains(flat.err, "could not write " + svg));
    CHECK(slurp(svg) == "<svg>an older pattern</svg>\n");
    CHECK(dir.entry_count() == 2);
  }
}

// An unwritable directory was found only by the write, after the whole solve
// (exit 3; the koala's deform 4.6 s, the bunny's flatten ~64 s), and the
// message said "an existing ro/new.obj is left unchanged" of a file that did
// not exist. The tests run as root, who may write anywhere: the CLI runs
// without CAP_DAC_OVERRIDE (setpriv), as a user without the permission.
TEST_CASE("cli robustness: an OUT in a directory that takes no new file is refused before the work", "[cli][robustness]") {
  if (!fs::exists("/usr/bin/setpriv")) {
    WARN("no /usr/bin/setpriv: the directory's permission cannot be taken from root");
    return;
  }
  CliScratch dir("read_only");
  fs::create_directories(dir.file("ro"));
  fs::permissions(dir.file("ro"), fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                      fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  const std::vector<std::string> without_override{"/usr/bin/setpriv", "--bounding-set", "-dac_override"};
  const std::string out = dir.file("ro/new.obj");
  const std::string expected = "error: OUT: cannot write " + out + ": no file can be created in directory " +
                               dir.file("ro") + " (Permission denied)";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"deform", mesh_path("formats/spot_lowres.obj"), out, "--scale", "1.2"},
        {"flatten", mesh_path("open/plane.off"), dir.file("ro/new.svg")},
        {"deform", "/nonexistent.obj", out}}) {  // before the input is even read
    const CliRun run = aniso::test::run_cli_under(without_override, args);
    INFO(describe(args, run));
    CHECK(run.exit_status == 2);
    CHECK(contains(run.err, args[0] == "flatten" ? "cannot write " + dir.file("ro/new.svg") : expected));
    CHECK_FALSE(contains(run.err, "left unchanged"));
    CHECK(run.out.empty());
  }
  fs::permissions(dir.file("ro"), fs::perms::owner_all);
  CHECK(dir.entry_count() == 1);
  CHECK(fs::is_empty(dir.file("ro")));  // no temporary file left by the probe
}

// A failed write names an existing OUT as left unchanged, and only then.
TEST_CASE("file io: a failed write says an existing file is left unchanged only when there is one", "[io]") {
  CliScratch dir("no_existing");
  const std::string missing_directory = dir.file("gone/new.obj");
  try {
    aniso::write_file_atomically(missing_directory, "x");
    FAIL("the write succeeded");
  } catch (const aniso::Error& e) {
    CHECK(std::string(e.what()) == "could not write " + missing_directory + ": No such file or directory");
  }
  CHECK(aniso::temporary_file_error_next_to(missing_directory) == ENOENT);
  CHECK(aniso::temporary_file_error_next_to(dir.file("new.obj")) == 0);
  CHECK(dir.entry_count() == 0);
}

TEST_CASE("cli robustness: OUT may be IN, and a failed write keeps IN intact", "[cli][robustness]") {
  CliScratch dir("in_place");
  const std::vector<std::string> edit{"--method", "andefgrad", "--scale", "1.4"};
  const std::string in = dir.copy_of_mesh("formats/spot_lowres.off", "spot.off");
  const std::string original = slurp(in);

  std::vector<std::string> failing{"deform", in, in};
  failing.insert(failing.end(), edit.begin(), edit.end());
  const CliRun failed = run_under_file_size_limit(8, failing);
  CHECK(failed.exit_status == 3);
  CHECK(contains(failed.err, "could not write " + in));
  CHECK(slurp(in) == original);

  std::vector<std::string> separate{"deform", in, dir.file("separate.off")};
  separate.insert(separate.end(), edit.begin(), edit.end());
  run_expecting(separate, 0);
  std::vector<std::string> in_place{"deform", in, in};
  in_place.insert(in_place.end(), edit.begin(), edit.end());
  run_expecting(in_place, 0);
  CHECK(slurp(in) == slurp(dir.file("separate.off")));  // the whole input was read before writing
  CHECK(slurp(in) != original);
  CHECK(dir.entry_count() == 2);
}

TEST_CASE("cli robustness: inputs that are not regular files are refused at once", "[cli][robustness]") {
  CliScratch dir("not_regular");
  for (const std::string name : {"zero.obj", "zero.stl", "zero.ply"}) {
    fs::create_symlink("/dev/zero", dir.file(name));  // endless bytes: read until memory ran out
    const CliRun run = aniso::test::run_cli({"info", dir.file(name)}, 20);
    INFO(describe({"info", dir.file(name)}, run));
    CHECK_FALSE(run.timed_out);
    CHECK(run.exit_status == 3);
    CHECK(contains(run.err, dir.file(name) + " is not a regular file (a character device)"));
  }
  REQUIRE(::mkfifo(dir.file("pipe.off").c_str(), 0600) == 0);  // no writer: a read blocked forever
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"info", dir.file("pipe.off")},
        std::vector<std::string>{"deform", dir.file("pipe.off"), dir.file("out.off")}}) {
    const CliRun run = aniso::test::run_cli(args, 20);
    INFO(describe(args, run));
    CHECK_FALSE(run.timed_out);
    CHECK(run.exit_status == 3);
    CHECK(contains(run.err, dir.file("pipe.off") + " is not a regular file (a FIFO)"));
  }
}

TEST_CASE("cli robustness: a header promising more than the file holds names the count and the size",
          "[cli][robustness]") {
  CliScratch dir("promises");
  std::string bytes = slurp(mesh_path("formats/spot_lowres_binary.ply"));
  const std::string declared = "element vertex 829";
  bytes.replace(bytes.find(declared), declared.size(), "element vertex 1000000000");
  const std::string ply = dir.file("billion.ply");
  aniso::write_file_atomically(ply, bytes);
  const CliRun run = run_expecting({"info", ply}, 3);
  CHECK(contains(run.err, "vertex 1000000000"));
  CHECK(contains(run.err, "at least 12000001654 bytes"));
  CHECK(contains(run.err, "bytes follow it"));
}

TEST_CASE("cli robustness: empty, hexadecimal values and unreadable files are refused naming the option",
          "[cli][robustness]") {
  CliScratch dir("values");
  const std::string in = mesh_path("formats/spot_lowres.obj");
  const std::string out = dir.file("out.obj");
  const std::string hex_field = dir.file("field.txt");
  aniso::write_file_atomically(hex_field, "0 1 0 0\n400 0x1p0 0 0\n");
  fs::create_directory(dir.file("selection"));
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"deform", in, out, "--scale", ""}, "--scale: needs a value, got an empty one"},
      {{"deform", in, out, "--iterations", ""}, "--iterations: needs a value, got an empty one"},
      {{"deform", in, out, "--rotate", ""}, "--rotate: needs a value, got an empty one"},
      {{"flatten", in, dir.file("p.svg"), "--compress", ""}, "--compress: needs a value, got an empty one"},
      {{"deform", in, out, "--scale", "0x1p1"}, "--scale: '0x1p1' is a hexadecimal number"},
      // A list names the number that is not one (it said "--scale: '' is empty").
      {{"deform", in, out, "--scale", "1,"}, "deform: error: --scale: SV: '' is empty"},
      {{"flatten", in, dir.file("p.svg"), "--compress", "0.8,x"}, "flatten: error: --compress: SV: 'x' is not a number"},
      {{"deform", in, out, "--method", "arap", "--move", "0,,1"}, "deform: error: --move: Y: '' is empty"},
      // Out of range by less than the sixth digit: printed so that it shows.
      {{"deform", in, out, "--rotate", "n:3600.0001"},
       "deform: error: --rotate: rotation angle (degrees) = 3600.0001 is out of range (-3600 .. 3600)"},
      {{"deform", in, out, "--iterations", "0x10"}, "--iterations: '0x10' is not an integer"},
      {{"deform", in, out, "--direction", "field:" + hex_field},
       "--direction: " + hex_field + " line 2: DX: '0x1p0' is a hexadecimal number"},
      {{"deform", in, out, "--select", "sphere:0,0,0,0x1p0"}, "sphere number 4: '0x1p0' is a hexadecimal number"},
      // Files named by options are named once, by deform and flatten alike.
      {{"flatten", in, dir.file("p.svg"), "--direction", "field:" + hex_field},
       "flatten: error: --direction: " + hex_field + " line 2: DX: '0x1p0' is a hexadecimal number"},
      // Amounts out of the core's range name their option too.
      {{"flatten", in, dir.file("p.svg"), "--compress", "0"}, "flatten: error: --compress: su must be positive, got 0"},
      {{"deform", in, out, "--scale", "1,0"}, "deform: error: --scale: scale sv must be positive, got 0"},
      {{"deform", in, out, "--shear", "1000"}, "deform: error: --shear: shear = 1000 is out of range (-100 .. 100)"},
      // The twist's range depends on the mesh (its bounding-box diagonal).
      {{"deform", in, out, "--twist", "0,1,0:1e6"},
       "deform: error: --twist: twist rate = 1e+06 degrees per unit turns the mesh by"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun run = run_expecting(args, 2);
    INFO(describe(args, run));
    CHECK(contains(run.err, message));
    CHECK(run.out.empty());
  }
  // A file an option names that cannot be read is a bad input file (exit 3),
  // as a missing mesh is; still named by its option.
  const std::vector<std::pair<std::vector<std::string>, std::string>> unreadable{
      {{"deform", in, out, "--select", "file:" + dir.file("selection")},
       "deform: error: --select: " + dir.file("selection") + " is a directory, not a regular file"},
      {{"deform", in, out, "--direction", "field:" + dir.file("none.txt")},
       "deform: error: --direction: cannot open " + dir.file("none.txt")},
      {{"flatten", in, dir.file("p.svg"), "--direction", "field:" + dir.file("none.txt")},
       "flatten: error: --direction: cannot open " + dir.file("none.txt")},
      {{"replay", dir.file("none.json"), out}, "replay: error: DOC: cannot open " + dir.file("none.json")},
      {{"flatten", in, dir.file("p.svg"), "--select", "file:" + dir.file("none.txt")},
       "flatten: error: --select: cannot open " + dir.file("none.txt")},
      {{"deform", in, out, "--op", dir.file("none.json")},
       "deform: error: --op: cannot open " + dir.file("none.json")},
  };
  for (const auto& [args, message] : unreadable) {
    const CliRun run = run_expecting(args, 3);
    INFO(describe(args, run));
    CHECK(contains(run.err, message));
    CHECK(run.out.empty());
  }
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("cli robustness: --iterations sets the steps of a rotation and twist, and caps a scale",
          "[cli][robustness]") {
  CliScratch dir("iterations");
  const std::string in = mesh_path("formats/spot_lowres.obj");
  const auto deform_with = [&](const std::vector<std::string>& edit, const std::string& iterations) {
    const std::string out = dir.file("out_" + std::to_string(dir.entry_count()) + ".obj");
    std::vector<std::string> args{"deform", in, out, "--iterations", iterations};
    args.insert(args.end(), edit.begin(), edit.end());
    const nlohmann::json result = stdout_json(run_expecting(args, 0));
    return std::make_pair(out, result);
  };
  const double size = aniso::bounding_box(aniso::read_mesh(in).mesh.V).diagonal();
  for (const std::vector<std::string>& edit :
       {std::vector<std::string>{"--rotate", "n:20", "--select", "sphere:0,0.5,0.8,0.3"},
        std::vector<std::string>{"--twist", "0,0,1:45"}}) {
    INFO(edit[0]);
    const auto one = deform_with(edit, "1");
    const auto three = deform_with(edit, "3");
    CHECK(one.second["iterations"] == 1);
    CHECK(three.second["iterations"] == 3);  // exactly the steps asked for
    // They were identical. The --rotate selection holds one vertex: the edit
    // moves the mesh by 1.4e-3 of its size, and 1 and 3 iterations differ by
    // 0.8e-4 of it, so the bound is 1e-5 (any difference is far above it).
    CHECK(max_position_difference(one.first, three.first) > 1e-5 * size);
  }
  const std::vector<std::string> scale{"--scale", "1.5,0.8"};
  const auto capped = deform_with(scale, "1");
  const auto longer = deform_with(scale, "5");
  CHECK(max_position_difference(capped.first, longer.first) > 1e-4 * size);
  // Cut off by the cap, and told so.
  CHECK(capped.second["converged"] == false);
  CHECK(capped.second["warnings"].dump().find("stopped at the iteration cap (1)") != std::string::npos);
  // Converged: a larger cap changes nothing.
  const auto converged = deform_with(scale, "300");
  const auto more = deform_with(scale, "600");
  CHECK(converged.second["converged"] == true);
  CHECK(converged.second["iterations"] < 300);
  CHECK(converged.second["warnings"].dump().find("iteration cap") == std::string::npos);
  CHECK(max_position_difference(converged.first, more.first) == 0.0);
}

TEST_CASE("cli robustness: --rotations coupled converges, --rotations steps turns again at every step",
          "[cli][robustness]") {
  CliScratch dir("rotations");
  const std::string in = mesh_path("formats/spot_lowres.obj");
  const auto deform_with = [&](const std::string& scheme, const std::string& iterations) {
    const std::string out = dir.file("out_" + std::to_string(dir.entry_count()) + ".obj");
    const nlohmann::json result = stdout_json(run_expecting(
        {"deform", in, out, "--rotate", "n:20", "--select", "sphere:0,0.5,0.8,0.3", "--rotations", scheme,
         "--iterations", iterations},
        0));
    return std::make_pair(out, result);
  };
  const double size = aniso::bounding_box(aniso::read_mesh(in).mesh.V).diagonal();
  const auto coupled = deform_with("coupled", "400");
  const auto coupled_more = deform_with("coupled", "800");
  CHECK(coupled.second["converged"] == true);
  CHECK(max_position_difference(coupled.first, coupled_more.first) == 0.0);
  const auto steps = deform_with("steps", "20");
  const auto more_steps = deform_with("steps", "40");
  CHECK(steps.second["iterations"] == 20);
  CHECK(max_position_difference(steps.first, more_steps.first) > 1e-4 * size);  // no fixed point
  CHECK(max_position_difference(coupled.first, steps.first) > 1e-3 * size);
  // The coupling is passed on: a much stronger one gives another shape.
  const std::string stiff = dir.file("stiff.obj");
  run_expecting({"deform", in, stiff, "--rotate", "n:20", "--select", "sphere:0,0.5,0.8,0.3",
                 "--rotation-coupling", "50", "--iterations", "400"},
                0);
  CHECK(max_position_difference(coupled.first, stiff) > 1e-4 * size);
}

TEST_CASE("cli robustness: --thicken is refused by the surface methods, which it cannot move, and moves the linear map",
          "[cli][robustness]") {
  // A scale along the normal leaves every edge lying in the surface as it
  // is: AnARAP and AnDefGrad would return the mesh unchanged, silently.
  const std::string in = mesh_path("closed/spot_triangulated.obj");
  for (const char* method : {"anarap", "andefgrad"}) {
    const CliRun run = run_expecting({"deform", in, temp_path("thick.obj"), "--method", method, "--thicken", "1.3"}, 2);
    INFO(method << ": " << run.err);
    CHECK(contains(run.err, "thickness (scale along the normal) = 1.3 has no effect with"));
    CHECK(contains(run.err, "scale across the direction"));
  }
  const std::string thick_path = temp_path("thick-linear.obj"), flat_path = temp_path("flat-linear.obj");
  run_expecting({"deform", in, thick_path, "--method", "linear", "--thicken", "1.3"}, 0);
  run_expecting({"deform", in, flat_path, "--method", "linear"}, 0);
  const aniso::Mesh thick = aniso::read_mesh(thick_path).mesh;
  const aniso::Mesh flat = aniso::read_mesh(flat_path).mesh;
  CHECK((thick.V - flat.V).rowwise().norm().maxCoeff() > 0.01);
}
