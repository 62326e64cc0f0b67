#include "avar/control/realtime_setup.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstring>

namespace avar::control {

RealtimeGrant apply_realtime(const RealtimeRequest& request) {
  RealtimeGrant grant;
  if (request.lock_memory) {
    if (::mlockall(MCL_CURRENT | MCL_FUTURE) == 0)
      grant.memory_locked = true;
    else
      grant.warnings.push_back(std::string("could not lock memory (") + std::strerror(errno) +
                               "): pages may be swapped out under load; raise 'ulimit -l' or run as root");
  }
  if (request.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(request.cpu), &set);
    const int err = request.cpu < CPU_SETSIZE ? pthread_setaffinity_np(pthread_self(), sizeof set, &set) : EINVAL;
    if (err == 0)
      grant.pinned = true;
    else
      grant.warnings.push_back("could not pin the loop to CPU " + std::to_string(request.cpu) + " (" + std::strerror(err) +
                               "): running on any CPU; this machine has " + std::to_string(::sysconf(_SC_NPROCESSORS_ONLN)) +
                               " online");
  }
  if (request.priority > 0) {
    const int lo = sched_get_priority_min(SCHED_FIFO), hi = sched_get_priority_max(SCHED_FIFO);
    sched_param param{};
    param.sched_priority = request.priority < lo ? lo : (request.priority > hi ? hi : request.priority);
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (err == 0)
      grant.fifo = true;
    else
      grant.warnings.push_back("could not run the loop under SCHED_FIFO priority " + std::to_string(param.sched_priority) +
                               " (" + std::strerror(err) +
                               "): running at normal priority, expect more wake-up lateness; run as root or grant "
                               "rtprio in /etc/security/limits.conf");
  }
  return grant;
}

void release_realtime(const RealtimeGrant& grant) {
  if (grant.fifo) {
    sched_param param{};
    pthread_setschedparam(pthread_self(), SCHED_OTHER, &param);
  }
  if (grant.memory_locked) ::munlockall();
  if (grant.pinned) {
    cpu_set_t all;
    CPU_ZERO(&all);
    for (long cpu = 0; cpu < ::sysconf(_SC_NPROCESSORS_CONF) && cpu < CPU_SETSIZE; ++cpu) CPU_SET(static_cast<unsigned>(cpu), &all);
    pthread_setaffinity_np(pthread_self(), sizeof all, &all);
  }
}

}  // namespace avar::control
