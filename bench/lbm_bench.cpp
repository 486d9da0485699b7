// Throughput of the MRT stream-collide kernels (LatticeBoltzmann<L>::Step) in MLUPS (million
// lattice-node updates per second), with a STREAM-like triad for the machine's memory bandwidth.
//
// Memory traffic per node update (double), A/B streaming with write-allocate:
//   D2Q9:  9 population reads + 9 writes (144 B) + write-allocate of the 9 written lines (72 B) =
//          216 B for a bare kernel; this one also reads the force (2 x 8 B) and writes rho, ux, uy
//          (3 x 8 B + 3 x 8 B write-allocate): 280 B per update (+8 B with a viscosity field);
//          in place (the AA pattern, the default; --pattern two for A/B) the population writes go
//          to lines just read, so no write-allocate for them: 144 + 16 + 48 = 208 B.
//   D3Q19: 19 reads + 19 writes + 19 write-allocate (456 B), force 3 x 8 B, rho and u 4 x 8 B
//          + write-allocate 4 x 8 B: 544 B per update (+8 B with a viscosity field); in place
//          (the AA pattern, --pattern inplace, the default) the writes go to lines just read, so
//          no write-allocate: 304 + 24 + 64 = 392 B.
// The bound is bandwidth / (B per update). Sizes are N^2 (D2Q9) or N^3 (D3Q19) nodes.
//
// usage: lbm_bench [--lattice d2q9|d3q19] [--sizes 256,321,512,1024,1281] [--threads 1,2]
//                  [--seconds 0.5] [--repeats 3] [--forcing split|guo] [--viscosity-field]
//                  [--stores auto|cached|streaming] [--pattern auto|two|inplace|compare]
// --pattern compare times the A/B and the in-place kernel alternately in one process (--repeats
// rounds) and prints both kernels' best and median MLUPS and the min / median / max of the
// per-round ratio in place / A/B.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/lbm/lattice_boltzmann.h"
#include "ehd_capsule/lbm/openmp_wait.h"

namespace {

using Clock = std::chrono::steady_clock;

std::vector<int> ParseList(const std::string& text) {
  std::vector<int> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    out.push_back(std::stoi(text.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// Triad a = b + s c over three arrays of n doubles each; counts 3 x 8 B + 8 B write-allocate.
double TriadBandwidthGBs(int threads, std::size_t n = std::size_t{1} << 25) {  // 3 x 256 MiB
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 0;
  for (int rep = 0; rep < 4; ++rep) {
    const auto t0 = Clock::now();
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::size_t k = 0; k < n; ++k) pa[k] = pb[k] + 0.5 * pc[k];
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    best = std::max(best, 32.0 * n / s * 1e-9);
  }
  if (a[n / 2] != 2.0) std::printf("(triad check failed)\n");
  return best;
}

}  // namespace

struct BenchOptions {
  double seconds = 0.5;
  int repeats = 3;
  ehd::ForcingScheme forcing = ehd::ForcingScheme::kSplitMomentum;
  bool viscosity_field = false;
  ehd::PopulationStores stores = ehd::PopulationStores::kAuto;
  ehd::StreamingPattern pattern = ehd::StreamingPattern::kAuto;
};

// The state every measurement starts from: a shear profile, a small force, optionally a
// viscosity field (a third of the nodes at another viscosity).
template <class Lattice>
void Prepare(Lattice& lb, int n, const BenchOptions& o) {
  lb.InitializeShear(1e-3 / n);
  for (std::size_t k = 0; k < lb.force_x().size(); ++k) lb.force_x()[k] = 1e-8 * (k % 7);
  if (o.viscosity_field) {
    std::vector<double> nu(lb.nodes(), 0.1);
    for (std::size_t k = 0; k < nu.size() / 3; ++k) nu[k] = 0.5;
    lb.SetViscosityField(nu);
  }
}

// A step count (even, so both parities of the in-place pattern are timed alike) that takes
// about `seconds`.
template <class Lattice>
int CalibrateSteps(Lattice& lb, double seconds) {
  int steps = 2;
  for (;;) {
    const auto t0 = Clock::now();
    for (int s = 0; s < steps; ++s) lb.Step();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    if (dt > 0.2 * seconds) return std::max(steps, 2 * static_cast<int>(steps * seconds / dt / 2));
    steps *= 2;
  }
}

struct Timing {
  double mlups;      // wall clock
  double cpu_mlups;  // from the process CPU time per thread: on a shared machine it does not
                     // count time the threads spent descheduled
};

template <class Lattice>
Timing TimeSteps(Lattice& lb, int steps, int threads) {
  const auto t0 = Clock::now();
  const std::clock_t c0 = std::clock();
  for (int s = 0; s < steps; ++s) lb.Step();
  const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
  const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / threads;
  const double updates = static_cast<double>(lb.nodes()) * steps;
  return {updates / dt * 1e-6, updates / cpu * 1e-6};
}

// Best wall-clock MLUPS and CPU-time MLUPS of `lb` over o.repeats runs of about o.seconds.
// The kernel's footprint in doubles per node: the populations (one or two arrays), the force,
// rho, u and the viscosity field.
template <class Lattice>
void Measure(Lattice& lb, int n, int threads, double bytes_per_update, double doubles_per_node,
             const BenchOptions& o) {
  Prepare(lb, n, o);
  const int steps = CalibrateSteps(lb, o.seconds);
  double best = 0, best_cpu = 0;
  for (int rep = 0; rep < o.repeats; ++rep) {
    const Timing t = TimeSteps(lb, steps, threads);
    best = std::max(best, t.mlups);
    best_cpu = std::max(best_cpu, t.cpu_mlups);
  }
  if (!lb.AllFinite()) std::printf("(non-finite state)\n");
  // A STREAM triad over the same footprint (three arrays of a third each), same threads: the
  // bandwidth the kernel's working set gets from wherever it lives (cache or DRAM).
  const double footprint = doubles_per_node * static_cast<double>(lb.nodes());
  const double triad = TriadBandwidthGBs(threads, static_cast<std::size_t>(footprint / 3.0));
  const double kernel_gbs = best * bytes_per_update * 1e-3;
  std::printf("%8d %8d %8d %10.1f %10.1f %12.2f %12.1f %10.0f %10.1f %8.0f %%\n", n, threads, steps,
              best, kernel_gbs, 1e3 / best, best_cpu, footprint * 8e-6, triad,
              100.0 * kernel_gbs / triad);
  std::fflush(stdout);
}

// --pattern compare: the two-lattice (A/B) and the in-place kernel of the same lattice in one
// process, timed alternately o.repeats times (rounds), so that both see the same machine
// state; prints each kernel's best and median MLUPS and the per-round ratios in place / A/B.
template <class Lattice>
void Compare(const ehd::LbmParameters& base, int n, int threads, const BenchOptions& o) {
  ehd::LbmParameters p = base;
  p.pattern = ehd::StreamingPattern::kTwoLattice;
  Lattice two(p);
  p.pattern = ehd::StreamingPattern::kInPlace;
  Lattice in_place(p);
  Prepare(two, n, o);
  Prepare(in_place, n, o);
  const int steps_two = CalibrateSteps(two, o.seconds);
  const int steps_in_place = CalibrateSteps(in_place, o.seconds);
  std::vector<double> mlups_two, mlups_in_place, ratios;
  for (int rep = 0; rep < o.repeats; ++rep) {
    mlups_two.push_back(TimeSteps(two, steps_two, threads).mlups);
    mlups_in_place.push_back(TimeSteps(in_place, steps_in_place, threads).mlups);
    ratios.push_back(mlups_in_place.back() / mlups_two.back());
  }
  if (!two.AllFinite() || !in_place.AllFinite()) std::printf("(non-finite state)\n");
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  };
  std::printf("%8d %8d %10.1f %10.1f %10.1f %10.1f %8.2f %8.2f %8.2f\n", n, threads,
              *std::max_element(mlups_two.begin(), mlups_two.end()), median(mlups_two),
              *std::max_element(mlups_in_place.begin(), mlups_in_place.end()),
              median(mlups_in_place), *std::min_element(ratios.begin(), ratios.end()),
              median(ratios), *std::max_element(ratios.begin(), ratios.end()));
  std::fflush(stdout);
}

int main(int argc, char** argv) {
  ehd::RestartWithPassiveOpenMpWait(argv);  // lbm/openmp_wait.h
  std::vector<int> sizes = {256, 321, 512, 1024, 1281};
  bool sizes_given = false;
  std::vector<int> thread_counts = {1, 2};
  BenchOptions o;
  bool d3q19 = false;
  bool compare = false;
  try {
    for (int k = 1; k < argc; ++k) {
      const std::string arg = argv[k];
      auto value = [&]() -> std::string {
        if (k + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
        return argv[++k];
      };
      if (arg == "--lattice") {
        const std::string v = value();
        if (v != "d2q9" && v != "d3q19") throw std::invalid_argument("--lattice d2q9|d3q19");
        d3q19 = v == "d3q19";
      } else if (arg == "--sizes") {
        sizes = ParseList(value());
        sizes_given = true;
      } else if (arg == "--threads") {
        thread_counts = ParseList(value());
      } else if (arg == "--seconds") {
        o.seconds = std::stod(value());
        if (!(o.seconds > 0)) throw std::invalid_argument("--seconds must be > 0");
      } else if (arg == "--repeats") {
        o.repeats = std::stoi(value());
        if (o.repeats < 1) throw std::invalid_argument("--repeats must be >= 1");
      } else if (arg == "--forcing") {
        const std::string v = value();
        if (v != "split" && v != "guo") throw std::invalid_argument("--forcing split|guo");
        o.forcing = v == "guo" ? ehd::ForcingScheme::kGuo : ehd::ForcingScheme::kSplitMomentum;
      } else if (arg == "--stores") {
        const std::string v = value();
        if (v == "auto") {
          o.stores = ehd::PopulationStores::kAuto;
        } else if (v == "cached") {
          o.stores = ehd::PopulationStores::kCached;
        } else if (v == "streaming") {
          o.stores = ehd::PopulationStores::kStreaming;
        } else {
          throw std::invalid_argument("--stores auto|cached|streaming");
        }
      } else if (arg == "--pattern") {
        const std::string v = value();
        if (v == "auto") {
          o.pattern = ehd::StreamingPattern::kAuto;
        } else if (v == "two") {
          o.pattern = ehd::StreamingPattern::kTwoLattice;
        } else if (v == "inplace") {
          o.pattern = ehd::StreamingPattern::kInPlace;
        } else if (v == "compare") {
          compare = true;
        } else {
          throw std::invalid_argument("--pattern auto|two|inplace|compare");
        }
      } else if (arg == "--viscosity-field") {
        o.viscosity_field = true;
      } else {
        throw std::invalid_argument("unknown option " + arg);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "lbm_bench: %s\nusage: lbm_bench [--lattice d2q9|d3q19] [--sizes 256,321,...] "
                 "[--threads 1,2] "
                 "[--seconds 0.5] [--repeats 3] [--forcing split|guo] [--viscosity-field] "
                 "[--stores auto|cached|streaming] [--pattern auto|two|inplace|compare]\n",
                 e.what());
    return 2;
  }
  if (d3q19 && !sizes_given) sizes = {64, 100, 128};
  if (compare) {
    if (o.stores == ehd::PopulationStores::kStreaming) {
      std::fprintf(stderr, "lbm_bench: --pattern compare needs --stores auto or cached\n");
      return 2;
    }
    std::printf(
        "%s MRT stream-collide, A/B against in place, shear walls, forcing %s%s, %d "
        "alternated rounds of >= %.2f s each\n",
        d3q19 ? "D3Q19" : "D2Q9", o.forcing == ehd::ForcingScheme::kGuo ? "guo" : "split",
        o.viscosity_field ? ", viscosity field" : "", o.repeats, o.seconds);
    std::printf("%8s %8s %10s %10s %10s %10s %8s %8s %8s\n", "N", "threads", "A/B best", "A/B med",
                "inpl best", "inpl med", "x min", "x median", "x max");
    for (int n : sizes) {
      for (int t : thread_counts) {
        ehd::LbmParameters p;
        p.nx = p.ny = n;
        p.nz = d3q19 ? n : 1;
        p.viscosity = 0.1;
        p.boundary = ehd::FluidBoundary::kShearWalls;
        p.forcing = o.forcing;
        p.threads = t;
        p.stores = o.stores;
        if (d3q19) {
          Compare<ehd::LatticeBoltzmann3D>(p, n, t, o);
        } else {
          Compare<ehd::LatticeBoltzmann2D>(p, n, t, o);
        }
      }
    }
    return 0;
  }
  // As LbmParameters::pattern resolves kAuto: in place, except D2Q9 with streaming stores.
  const bool in_place = o.pattern == ehd::StreamingPattern::kInPlace ||
                        (o.pattern == ehd::StreamingPattern::kAuto &&
                         (d3q19 || o.stores != ehd::PopulationStores::kStreaming));
  const double bytes_per_update =
      (d3q19 ? (in_place ? 392.0 : 544.0) : (in_place ? 208.0 : 280.0)) +
      (o.viscosity_field ? 8.0 : 0.0);
  std::printf("%s MRT stream-collide%s, shear walls, forcing %s%s, best of %d runs of >= %.2f s\n",
              d3q19 ? "D3Q19" : "D2Q9", in_place ? " (in place)" : "",
              o.forcing == ehd::ForcingScheme::kGuo ? "guo" : "split",
              o.viscosity_field ? ", viscosity field" : "", o.repeats, o.seconds);
  for (int t : thread_counts) {
    const double bw = TriadBandwidthGBs(t);
    std::printf("triad bandwidth, %d thread(s): %.1f GB/s -> bound %.0f MLUPS at %.0f B/update\n",
                t, bw, bw * 1e3 / bytes_per_update, bytes_per_update);
  }
  const int q = d3q19 ? 19 : 9, dimension = d3q19 ? 3 : 2;
  const double doubles_per_node =
      (in_place ? q : 2 * q) + 2 * dimension + 1 + (o.viscosity_field ? 1 : 0);
  std::printf("%8s %8s %8s %10s %10s %12s %12s %10s %10s %10s\n", "N", "threads", "steps", "MLUPS",
              "GB/s", "ns/update", "cpu MLUPS", "MB", "triad GB/s", "of triad");
  for (int n : sizes) {
    for (int t : thread_counts) {
      ehd::LbmParameters p;
      p.nx = p.ny = n;
      p.nz = d3q19 ? n : 1;
      p.viscosity = 0.1;
      p.boundary = ehd::FluidBoundary::kShearWalls;
      p.forcing = o.forcing;
      p.threads = t;
      p.stores = o.stores;
      p.pattern = o.pattern;
      if (d3q19) {
        ehd::LatticeBoltzmann3D lb(p);
        Measure(lb, n, t, bytes_per_update, doubles_per_node, o);
      } else {
        ehd::LatticeBoltzmann2D lb(p);
        Measure(lb, n, t, bytes_per_update, doubles_per_node, o);
      }
    }
  }
  return 0;
}
