// Re-executes the program with OMP_WAIT_POLICY=PASSIVE; see openmp_wait.h.
#include "ehd_capsule/lbm/openmp_wait.h"

#include <unistd.h>

#include <cstdlib>

namespace ehd {

void RestartWithPassiveOpenMpWait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // execv returns only on failure: go on with the default policy.
}

}  // namespace ehd
