// anisoform_bench --mesh NAME [--runs N] [--iterations N] [--only IMPL,...] [--verbose]
//
// Times the standard problem (bench/problems.h) with every implementation in
// the same process, interleaved run by run, and prints one JSON line per
// implementation on stdout:
//   {"mesh":..., "vertices":..., "impl":..., "precompute_ms":..., "iteration_ms":...}
// (medians over the runs), then one summary line of same-run ratios on stderr.
// See bench/README.md for the exact definitions.
#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "anisoform/error.h"
#include "converge.h"
#include "impls.h"
#include "problems.h"

namespace {

using aniso_bench::median_of;
using aniso_bench::Problem;
using aniso_bench::Sample;

const char* kUsage =
    "usage: anisoform_bench --mesh cyl1k|cyl10k|cyl50k|cyl200k|PATH [--runs N]\n"
    "                       [--iterations N] [--only IMPL[,IMPL...]] [--clock wall|cpu]\n"
    "                       [--verbose] [--converge TOL [--max-iterations N]]\n"
    "  --runs N        runs per implementation (medians); default 5, 3 above 100k vertices\n"
    "  --iterations N  ARAP/AnARAP/CGAL iterations per timed call (default 10)\n"
    "  --only LIST     eigen-ldlt, anisoform-arap, anisoform-anarap,\n"
    "                  anisoform-andefgrad, cgal-arap (default: all)\n"
    "  --clock KIND    wall (default) or cpu: this thread's CPU time, robust on a\n"
    "                  loaded machine (see bench/README.md for what changes)\n"
    "  --verbose       per-run details on stderr\n"
    "  --converge TOL  instead: ARAP, AnARAP (a stretch; a twist: coupled rotations) and the\n"
    "                  flattening solved to the relative\n"
    "                  energy change TOL, plain local/global and accelerated: iterations,\n"
    "                  ms and energy per row (cap --max-iterations, default 5000);\n"
    "                  --only then takes anisoform-arap, anisoform-anarap,\n"
    "                  anisoform-anarap-twist, anisoform-flatten\n"
    "Run natively with GLIBC_TUNABLES=glibc.malloc.mmap_max=0:glibc.malloc.trim_threshold=68719476736\n"
    "(without it, the equivalent mallopt() settings are applied at start-up).\n";

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "anisoform_bench: %s\n%s", message.c_str(), kUsage);
  std::exit(2);
}

int parse_positive(const std::string& option, const std::string& value) {
  char* end = nullptr;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || v < 1 || v > 1000000) {
    usage_error(option + " needs a positive integer, got '" + value + "'");
  }
  return static_cast<int>(v);
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

// GLIBC_TUNABLES is read by the loader; when it is missing, the same two
// settings are applied through mallopt() before any large allocation: freed
// blocks stay in the heap instead of being unmapped and faulted in again.
const char* configure_malloc() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::string(tunables).find("glibc.malloc.mmap_max=0") != std::string::npos) {
    return "GLIBC_TUNABLES";
  }
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 0x7fffffff);
  return "mallopt(M_MMAP_MAX=0, M_TRIM_THRESHOLD=2^31-1) (GLIBC_TUNABLES not set)";
}

struct Impl {
  std::string name;
  std::function<Sample(const Problem&)> run;
  std::vector<Sample> samples;
};

}  // namespace

int main(int argc, char** argv) {
  const char* malloc_mode = configure_malloc();
  std::string mesh_name;
  int runs = 0, iterations = 10;
  bool verbose = false;
  double converge_tolerance = -1.0;
  int max_iterations = 5000;
  std::set<std::string> only;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&]() -> std::string {
      if (a + 1 >= argc) usage_error(arg + " needs a value");
      return argv[++a];
    };
    if (arg == "--mesh") {
      mesh_name = value();
    } else if (arg == "--runs") {
      runs = parse_positive(arg, value());
    } else if (arg == "--iterations") {
      iterations = parse_positive(arg, value());
    } else if (arg == "--only") {
      std::stringstream list(value());
      std::string item;
      while (std::getline(list, item, ',')) only.insert(item);
    } else if (arg == "--clock") {
      const std::string kind = value();
      if (kind == "wall") {
        aniso_bench::set_clock(aniso_bench::ClockKind::Wall);
      } else if (kind == "cpu") {
        aniso_bench::set_clock(aniso_bench::ClockKind::Cpu);
      } else {
        usage_error("--clock needs wall or cpu, got '" + kind + "'");
      }
    } else if (arg == "--converge") {
      const std::string text = value();
      char* end = nullptr;
      converge_tolerance = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !(converge_tolerance > 0.0) || converge_tolerance >= 1.0) {
        usage_error("--converge needs a tolerance in (0, 1), got '" + text + "'");
      }
    } else if (arg == "--max-iterations") {
      max_iterations = parse_positive(arg, value());
    } else if (arg == "--verbose") {
      verbose = true;
    } else if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      usage_error("unknown argument '" + arg + "'");
    }
  }
  if (mesh_name.empty()) usage_error("--mesh is required");

  Problem problem;
  try {
    problem = aniso_bench::make_problem(mesh_name);
  } catch (const aniso::Error& e) {
    std::fprintf(stderr, "anisoform_bench: %s: %s\n", mesh_name.c_str(), e.what());
    return e.code() == aniso::ErrorCode::BadParameter ? 2 : 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "anisoform_bench: %s: %s\n", mesh_name.c_str(), e.what());
    return 3;
  }
  const int n = problem.mesh.num_vertices();
  if (runs == 0) runs = n > 100000 ? 3 : 5;

  if (converge_tolerance > 0.0) {
    for (const std::string& name : only) {
      if (!aniso_bench::is_convergence_row(name)) usage_error("unknown row '" + name + "' in --only for --converge");
    }
    return aniso_bench::run_convergence(problem, converge_tolerance, runs, max_iterations, only);
  }

  const int solves = 5;   // eigen-ldlt solves per run (median)
  const int changes = 4;  // andefgrad changes of amount per run (median)
  std::vector<Impl> impls = {
      {"eigen-ldlt", [&](const Problem& p) { return aniso_bench::run_eigen_ldlt(p, solves); }, {}},
      {"anisoform-arap", [&](const Problem& p) { return aniso_bench::run_anisoform_arap(p, iterations); }, {}},
      {"anisoform-anarap", [&](const Problem& p) { return aniso_bench::run_anisoform_anarap(p, iterations); }, {}},
      {"anisoform-andefgrad", [&](const Problem& p) { return aniso_bench::run_anisoform_andefgrad(p, changes); }, {}},
      {"cgal-arap", [&](const Problem& p) { return aniso_bench::run_cgal_arap(p, iterations); }, {}},
  };
  for (const std::string& name : only) {
    bool known = false;
    for (const Impl& impl : impls) known = known || impl.name == name;
    if (!known) usage_error("unknown implementation '" + name + "' in --only");
  }
  std::vector<Impl*> active;
  for (Impl& impl : impls) {
    if (!only.empty() && !only.count(impl.name)) continue;
    if (impl.name == "cgal-arap" && !aniso_bench::have_cgal()) {
      std::fprintf(stderr, "anisoform_bench: built without CGAL: no cgal-arap row\n");
      continue;
    }
    active.push_back(&impl);
  }

  if (verbose) {
    std::fprintf(stderr,
                 "mesh %s: %d vertices, %d triangles; long axis %c (height %g), move along %c by %g; "
                 "%zu fixed, %zu moved, %d in the top half; %d runs, %d iterations per call; %s clock; malloc: %s\n",
                 mesh_name.c_str(), n, problem.mesh.num_triangles(), "xyz"[problem.long_axis], problem.height,
                 "xyz"[problem.move_axis], problem.offset[problem.move_axis], problem.fixed.size(),
                 problem.moved.size(), static_cast<int>(problem.top_half.sum()), runs, iterations,
                 aniso_bench::clock_kind() == aniso_bench::ClockKind::Cpu ? "cpu" : "wall", malloc_mode);
  }

  // Pre-fault the heap once: with the malloc settings above, freed memory stays
  // in the heap, so no implementation (in particular not the first one of the
  // first run) pays the process's first touch of fresh pages (~10 us per 4 KiB
  // here, TOOLCHAIN.md §7). About 4 KiB per vertex covers the peak use.
  {
    const std::size_t bytes = std::min<std::size_t>(std::size_t(2) << 30,
                                                    std::max<std::size_t>(std::size_t(64) << 20, std::size_t(4096) * n));
    // Through a volatile pointer: the compiler may not elide the
    // malloc/memset/free sequence (GCC does otherwise).
    static void* (*volatile touch)(void*, int, std::size_t) = std::memset;
    if (void* block = std::malloc(bytes)) {
      touch(block, 1, bytes);
      std::free(block);
    }
  }

  // Interleaved: run r times every implementation once, so a slow phase of the
  // shared machine hits all of them alike.
  for (int r = 0; r < runs; ++r) {
    for (Impl* impl : active) {
      try {
        impl->samples.push_back(impl->run(problem));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "anisoform_bench: %s failed on %s: %s\n", impl->name.c_str(), mesh_name.c_str(),
                     e.what());
        return 3;
      }
      if (verbose) {
        const Sample& s = impl->samples.back();
        std::fprintf(stderr,
                     "  run %d %-20s precompute %9.3f ms (setup %8.3f)  iteration %8.3f ms (first call %8.3f, "
                     "%d it)  %s %.4g\n",
                     r, impl->name.c_str(), s.precompute_ms, s.setup_ms, s.iteration_ms, s.first_call_ms,
                     s.iterations, impl->name == "eigen-ldlt" ? "residual" : "mean |dv|", s.mean_displacement);
      }
    }
  }

  std::map<std::string, const Impl*> by_name;
  for (const Impl* impl : active) {
    std::vector<double> pre, it;
    for (const Sample& s : impl->samples) {
      pre.push_back(s.precompute_ms);
      it.push_back(s.iteration_ms);
    }
    const long factor_nonzeros = impl->samples.empty() ? 0 : impl->samples.back().factor_nonzeros;
    const std::string nnz = factor_nonzeros > 0 ? ",\"factor_nnz\":" + std::to_string(factor_nonzeros) : "";
    std::printf("{\"mesh\":%s,\"vertices\":%d,\"impl\":\"%s\",\"precompute_ms\":%.3f,\"iteration_ms\":%.3f%s}\n",
                json_string(mesh_name).c_str(), n, impl->name.c_str(), median_of(pre), median_of(it), nnz.c_str());
    by_name[impl->name] = impl;
  }
  std::fflush(stdout);

  // Ratios: per run (both numbers from the same run), then the median.
  auto ratio = [&](const std::string& a, const std::string& b, bool precompute) -> std::string {
    if (!by_name.count(a) || !by_name.count(b)) return "n/a";
    std::vector<double> q;
    const auto& sa = by_name[a]->samples;
    const auto& sb = by_name[b]->samples;
    for (std::size_t k = 0; k < sa.size() && k < sb.size(); ++k) {
      const double x = precompute ? sa[k].precompute_ms : sa[k].iteration_ms;
      const double y = precompute ? sb[k].precompute_ms : sb[k].iteration_ms;
      q.push_back(x / y);
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", median_of(q));
    return buf;
  };
  std::fprintf(stderr,
               "summary %s (%d vertices, %d runs, %s clock, same-run ratios, median): "
               "arap/ldlt %s (goal <= 2.5), anarap/ldlt %s (goal <= 2.5), "
               "cgal/arap %s (goal >= 3), cgal/anarap %s (goal >= 3), "
               "andefgrad/ldlt %s (goal <= 1.3), "
               "precompute arap/ldlt %s (goal <= 1.5), anarap/ldlt %s, andefgrad/ldlt %s\n",
               mesh_name.c_str(), n, runs,
               aniso_bench::clock_kind() == aniso_bench::ClockKind::Cpu ? "cpu" : "wall", ratio("anisoform-arap", "eigen-ldlt", false).c_str(),
               ratio("anisoform-anarap", "eigen-ldlt", false).c_str(),
               ratio("cgal-arap", "anisoform-arap", false).c_str(),
               ratio("cgal-arap", "anisoform-anarap", false).c_str(),
               ratio("anisoform-andefgrad", "eigen-ldlt", false).c_str(),
               ratio("anisoform-arap", "eigen-ldlt", true).c_str(),
               ratio("anisoform-anarap", "eigen-ldlt", true).c_str(),
               ratio("anisoform-andefgrad", "eigen-ldlt", true).c_str());
  return 0;
}
