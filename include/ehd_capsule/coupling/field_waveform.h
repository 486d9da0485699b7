// The applied field's time dependence E(t) = E f(t) (scene keys electric.waveform, frequency,
// phase, offset, pulse_width, pulse_period, pulse_count; issue #45 item 5), E the amplitude set
// by Ca_E (live changes included). The leaky-dielectric model here is quasi-static (no charge
// relaxation), so it holds for fields that change slowly against the charge relaxation time
// eps / sigma: the force then follows E(t)^2 at every instant.
#pragma once

#include <string>

#include "ehd_capsule/scene/scene.h"

namespace ehd {

// f(t): 1 (dc); offset + cos(2 pi frequency t + phase) (ac); 1 for t mod period in
// [0, pulse_width) while t < pulse_count periods (count 0: for ever), else 0 (pulses).
double FieldWaveformFactor(const SceneElectric& electric, double t);

// True when f changes with time (ac, pulses).
bool IsTimeDependent(const SceneElectric& electric);

// The waveform against the step: an ac period must span at least kMinStepsPerPeriod steps, a
// pulse and a gap between pulses (when there is one) at least kMinStepsPerPulse. time_per_step
// is one lattice step in the scene's unit of time (k with shear, else LatticeUnits::dt). Returns
// "" when resolved, else the reason, naming the key, the steps it spans and the limit.
constexpr double kMinStepsPerPeriod = 20;
constexpr double kMinStepsPerPulse = 4;
std::string WaveformResolutionProblem(const SceneElectric& electric, double time_per_step);

}  // namespace ehd
