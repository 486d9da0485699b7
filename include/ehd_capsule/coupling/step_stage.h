// One stage of the coupled time step (song2019 sec. 3.6): electric, membrane, spread, viscosity
// contrast, fluid, markers, diagnostics. A Simulation builds the stages its scene needs and no
// others, runs them in order each step, and assembles from them (never by hand beside the
// construction) the printed pipeline and the checkpoint: each stage describes itself and saves
// and restores its own state in a named checkpoint section.
//
// Stages are class templates over the dimension (coupling/stages/), sharing the bodies they act
// on (StepData<D>, coupling/body.h) by reference; the interface itself names no dimension. The
// contracts are in docs/architecture.md.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/checkpoint_io.h"

namespace ehd {

struct SimulationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws SimulationError("step N: what"): how every watchdog and solver failure is reported.
[[noreturn]] void FailStep(long step, const std::string& what);

// The largest lattice Mach number |u| / c_s over the nodes of a velocity field given by its
// components; FailStep names the first node whose speed is not finite.
double MaxLatticeMach(long step, const std::vector<const std::vector<double>*>& components);

// A number as the messages print it (shortest round-trip-free form, as std::ostream does).
std::string FormatValue(double v);

class StepStage {
 public:
  virtual ~StepStage() = default;
  // Short name: the checkpoint section and the pipeline label ("electric", "fluid", ...).
  virtual const char* name() const = 0;
  // The pipeline text of this stage, without the label: one line, or several separated by '\n'.
  virtual std::string Describe() const = 0;
  // Back to the initial state (construction, Simulation::Reset).
  virtual void Reset() = 0;
  // This stage's part of step `step` (the number of the step being taken).
  virtual void Run(long step) = 0;
  virtual void Save(CheckpointWriter& out) const = 0;
  // Reads what Save wrote; the shared body data are restored before any stage.
  virtual void Restore(CheckpointReader& in) = 0;
};

}  // namespace ehd
