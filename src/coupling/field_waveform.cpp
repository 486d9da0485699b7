// The applied field's time dependence (coupling/field_waveform.h).
#include "ehd_capsule/coupling/field_waveform.h"

#include <cmath>

#include "ehd_capsule/coupling/step_stage.h"

namespace ehd {

double FieldWaveformFactor(const SceneElectric& e, double t) {
  switch (e.waveform) {
    case FieldWaveform::kAc:
      return e.offset + std::cos(2.0 * M_PI * e.frequency * t + e.phase);
    case FieldWaveform::kPulses: {
      if (t < 0.0) return 0.0;
      const double cycles = std::floor(t / e.pulse_period);
      if (e.pulse_count > 0 && cycles >= e.pulse_count) return 0.0;
      return t - cycles * e.pulse_period < e.pulse_width ? 1.0 : 0.0;
    }
    case FieldWaveform::kDc:
      break;
  }
  return 1.0;
}

bool IsTimeDependent(const SceneElectric& e) { return e.waveform != FieldWaveform::kDc; }

std::string WaveformResolutionProblem(const SceneElectric& e, double time_per_step) {
  if (!(time_per_step > 0.0)) return "";
  auto problem = [](const std::string& what, double steps, double limit,
                    const std::string& remedy) {
    return what + " spans " + FormatValue(steps) + " lattice steps, fewer than " +
           FormatValue(limit) + ": " + remedy;
  };
  if (e.waveform == FieldWaveform::kAc) {
    const double steps = 1.0 / (e.frequency * time_per_step);
    if (steps < kMinStepsPerPeriod) {
      return problem("a period of 'electric.frequency' = " + FormatValue(e.frequency), steps,
                     kMinStepsPerPeriod,
                     "lower it, or refine the step (N, numerics.membrane_substeps)");
    }
  } else if (e.waveform == FieldWaveform::kPulses) {
    const double on = e.pulse_width / time_per_step;
    if (on < kMinStepsPerPulse) {
      return problem("'electric.pulse_width' = " + FormatValue(e.pulse_width), on,
                     kMinStepsPerPulse, "lengthen it, or refine the step");
    }
    const double off = (e.pulse_period - e.pulse_width) / time_per_step;
    if (off > 0.0 && off < kMinStepsPerPulse) {
      return problem("the gap 'electric.pulse_period' - 'electric.pulse_width' = " +
                         FormatValue(e.pulse_period - e.pulse_width),
                     off, kMinStepsPerPulse,
                     "make it 0 (a steady field) or lengthen it, or refine the step");
    }
  }
  return "";
}

}  // namespace ehd
