#include "avar/control/realtime_setup.hpp"

#include <pthread.h>
#include <sched.h>

#include <gtest/gtest.h>

namespace avar::control {
namespace {

TEST(RealtimeSetup, EitherGrantsEachRequestOrSaysWhyNot) {
  const RealtimeGrant grant = apply_realtime({10, true, 0});
  int policy = 0;
  sched_param param{};
  pthread_getschedparam(pthread_self(), &policy, &param);
  EXPECT_EQ(grant.fifo, policy == SCHED_FIFO);
  const std::size_t refused = (grant.fifo ? 0 : 1) + (grant.memory_locked ? 0 : 1) + (grant.pinned ? 0 : 1);
  EXPECT_EQ(grant.warnings.size(), refused);
  for (const std::string& w : grant.warnings) EXPECT_NE(w.find("could not"), std::string::npos) << w;
  release_realtime(grant);
  pthread_getschedparam(pthread_self(), &policy, &param);
  EXPECT_EQ(policy, SCHED_OTHER);
}

TEST(RealtimeSetup, ImpossibleCpuIsAWarningNotAFailure) {
  const RealtimeGrant grant = apply_realtime({0, false, 100000});
  EXPECT_FALSE(grant.pinned);
  ASSERT_EQ(grant.warnings.size(), 1u);
  EXPECT_NE(grant.warnings[0].find("could not pin the loop to CPU 100000"), std::string::npos) << grant.warnings[0];
}

TEST(RealtimeSetup, NothingRequestedNothingChanged) {
  const RealtimeGrant grant = apply_realtime({});
  EXPECT_FALSE(grant.fifo || grant.memory_locked || grant.pinned);
  EXPECT_TRUE(grant.warnings.empty());
}

}  // namespace
}  // namespace avar::control
