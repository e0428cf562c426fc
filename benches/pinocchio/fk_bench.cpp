// Pinocchio's rigid forward kinematics (pinocchio::forwardKinematics) on the robots of
// robots.hpp, the header the ops bench binary writes (PPOE_PINOCCHIO_EXPORT=DIR) from
// ppoe-build's chains. Run by scripts/bench-report.sh; built with -O3 for the default
// target, as ppoe's benches are (no -march=native).
//
// For each robot: the model is built joint by joint (RX/RY/RZ or RevoluteUnaligned with
// the exported placements), the tip pose oMi[n]·tip of every test configuration is
// compared with ppoe's (exit status 1 if any element differs by more than 1e-12), then
// BATCHES batches of CALLS calls on the first configuration are timed (arguments 1 and 2;
// argument 3, if given, names the only robot to run; argument 4 "fixed" skips what
// follows), then the same number of batches
// cycling through 256 configurations uniform in [-1, 1] per joint (the batch benchmarks'
// distribution, for the per-configuration comparison with ppoe's batch); two lines per robot:
//   pinocchio robot=<name> joints=<n> ns_per_call=<median> min_ns=<f> batches=<b>
//   calls=<c> max_abs_err=<e>
//   pinocchio_batch robot=<name> joints=<n> ns_per_config=<median> configs=256 batches=<b>
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/kinematics.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "robots.hpp"

namespace {

pinocchio::SE3 se3(const double* a) {
  Eigen::Matrix3d r;
  r << a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8];
  return pinocchio::SE3(r, Eigen::Vector3d(a[9], a[10], a[11]));
}

pinocchio::Model build(const RobotTable& t) {
  pinocchio::Model model;
  pinocchio::JointIndex parent = 0;
  for (int i = 0; i < t.n; ++i) {
    const pinocchio::SE3 place = se3(t.place[i]);
    const std::string name = "j" + std::to_string(i + 1);
    switch (t.kind[i]) {
      case 0: parent = model.addJoint(parent, pinocchio::JointModelRX(), place, name); break;
      case 1: parent = model.addJoint(parent, pinocchio::JointModelRY(), place, name); break;
      case 2: parent = model.addJoint(parent, pinocchio::JointModelRZ(), place, name); break;
      default:
        parent = model.addJoint(
            parent,
            pinocchio::JointModelRevoluteUnaligned(t.axis[i][0], t.axis[i][1], t.axis[i][2]),
            place, name);
    }
  }
  return model;
}

// Largest |element| difference between Pinocchio's tip poses and ppoe's, over the cases.
double check(const RobotTable& t, const pinocchio::Model& model, pinocchio::Data& data) {
  const pinocchio::SE3 tip = se3(t.tip);
  double worst = 0.0;
  for (int c = 0; c < t.cases; ++c) {
    Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(t.q + c * t.n, t.n);
    pinocchio::forwardKinematics(model, data, q);
    const pinocchio::SE3 m = data.oMi[t.n] * tip;
    const double* e = t.expected[c];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) worst = std::max(worst, std::fabs(m.rotation()(i, j) - e[3 * i + j]));
      worst = std::max(worst, std::fabs(m.translation()(i) - e[9 + i]));
    }
  }
  return worst;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// As many configurations as the batch benchmarks of benches/ops.rs (BATCH) use.
constexpr int kConfigs = 256;

// Median ns per call over `batches` batches of about `calls` calls, cycling through kConfigs
// configurations uniform in [-1, 1] per joint (the distribution of the batch benchmarks; a
// fixed seed), so that the branches of sin/cos see varied angles as the batch's do.
double time_configurations(const pinocchio::Model& model, pinocchio::Data& data, int n, int batches,
                           int calls) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::VectorXd> qs(kConfigs, Eigen::VectorXd(n));
  for (auto& q : qs)
    for (int j = 0; j < n; ++j) q(j) = u(rng);
  const int rounds = std::max(1, calls / kConfigs);
  std::vector<double> ns;
  for (int b = 0; b < batches; ++b) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < rounds; ++r) {
      for (const auto& q : qs) {
        asm volatile("" : : "g"(q.data()), "g"(&data) : "memory");
        pinocchio::forwardKinematics(model, data, q);
      }
    }
    const auto t1 = std::chrono::steady_clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / (rounds * kConfigs));
  }
  return median(ns);
}

}  // namespace

int main(int argc, char** argv) {
  const int batches = argc > 1 ? std::atoi(argv[1]) : 31;
  const int calls = argc > 2 ? std::atoi(argv[2]) : 20000;
  const std::string only = argc > 3 ? argv[3] : "";
  int status = 0;
  for (const RobotTable& t : kRobots) {
    if (!only.empty() && only != t.name) continue;
    const pinocchio::Model model = build(t);
    pinocchio::Data data(model);
    const double err = check(t, model, data);
    if (!(err <= 1e-12)) {
      std::fprintf(stderr, "pinocchio: robot %s: tip pose differs from ppoe's by %.3e\n", t.name, err);
      status = 1;
      continue;
    }
    Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(t.q, t.n);
    std::vector<double> ns;
    for (int b = 0; b < batches; ++b) {
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < calls; ++i) {
        // The barrier keeps the compiler from hoisting or dropping the loop-invariant call.
        asm volatile("" : : "g"(q.data()), "g"(&data) : "memory");
        pinocchio::forwardKinematics(model, data, q);
      }
      const auto t1 = std::chrono::steady_clock::now();
      ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / calls);
    }
    std::printf("pinocchio robot=%s joints=%d ns_per_call=%.2f min_ns=%.2f batches=%d calls=%d max_abs_err=%.3e\n",
                t.name, t.n, median(ns), *std::min_element(ns.begin(), ns.end()), batches, calls, err);
    // Argument 4 "fixed": the fixed-configuration batches only (bench_report.py's
    // instruction count, whose difference of two runs must scale with one loop).
    if (argc > 4 && std::string(argv[4]) == "fixed") continue;
    const double varied = time_configurations(model, data, t.n, batches, calls);
    std::printf("pinocchio_batch robot=%s joints=%d ns_per_config=%.2f configs=%d batches=%d\n", t.name,
                t.n, varied, kConfigs, batches);
  }
  return status;
}
