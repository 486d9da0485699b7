// The OpenMP wait policy of the fluid kernels' parallel regions.
//
// libgomp's threads spin at barriers by default; on a shared machine (this project's 2-core
// development and CI machines run several jobs) the spinning threads take the cores the working
// threads need, and a 2-thread D3Q19 step runs at 15 instead of 25 MLUPS (lbm_bench, docs/lbm.md).
// The policy is read once, when the OpenMP runtime loads, before main: so a program that wants
// the passive policy sets OMP_WAIT_POLICY=PASSIVE and re-executes itself, once, at the start of
// main. A policy the user set (OMP_WAIT_POLICY in the environment) is kept.
#pragma once

namespace ehd {

// If OMP_WAIT_POLICY is unset: sets it to PASSIVE and re-executes /proc/self/exe with argv
// (does not return). Returns (and the program goes on with the runtime's default) if the
// variable is set or the re-execution fails.
void RestartWithPassiveOpenMpWait(char** argv);

}  // namespace ehd
