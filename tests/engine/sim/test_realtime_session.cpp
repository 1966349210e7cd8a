// The realtime session: what it reports is what the kernel says the thread has, helper threads are
// lowered (and moved off a pinned CPU), and everything is restored when the session ends.
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <string>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "tacta/sim/realtime.hpp"

namespace {

using tacta::RealtimeOptions;
using tacta::RealtimeSession;

int policy_of_this_thread(int* priority = nullptr) {
  int policy = 0;
  sched_param p{};
  pthread_getschedparam(pthread_self(), &policy, &p);
  if (priority != nullptr) *priority = p.sched_priority;
  return policy;
}

uint64_t locked_kb() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmLck:", 0) == 0) return std::stoull(line.substr(6));
  return 0;
}

// A helper thread that parks until told to go, and reports its nice value and CPUs on request.
struct Helper {
  std::atomic<int> tid{0};
  std::atomic<bool> quit{false};
  std::thread thread{[this] {
    tid.store(static_cast<int>(syscall(SYS_gettid)));
    while (!quit.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }};
  Helper() {
    while (tid.load() == 0) std::this_thread::yield();
  }
  ~Helper() {
    quit.store(true);
    thread.join();
  }
  int nice() const { return getpriority(PRIO_PROCESS, static_cast<id_t>(tid.load())); }
  bool may_run_on(int cpu) const {
    cpu_set_t set;
    sched_getaffinity(tid.load(), sizeof set, &set);
    return CPU_ISSET(cpu, &set);
  }
};

TEST(RealtimeSession, ReportsWhatTheKernelGrantedAndRestoresIt) {
  const int policy_before = policy_of_this_thread();
  const int helper_nice_before = [] {
    errno = 0;
    return getpriority(PRIO_PROCESS, 0);
  }();
  Helper helper;
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  {
    RealtimeOptions options;
    options.priority = 80;
    options.cpu = 0;
    RealtimeSession session(options);
    const tacta::RealtimeGrant& g = session.grant();
    int priority = 0;
    const int policy = policy_of_this_thread(&priority);
    if (g.scheduler == "SCHED_FIFO") {
      EXPECT_EQ(policy, SCHED_FIFO);
      EXPECT_EQ(priority, 80);
      EXPECT_TRUE(g.scheduler_note.empty()) << g.scheduler_note;
    } else {
      // Refused (no CAP_SYS_NICE here): still SCHED_OTHER, and the report says why and what instead.
      EXPECT_EQ(policy, SCHED_OTHER);
      EXPECT_NE(g.scheduler_note.find("fallback"), std::string::npos) << g.scheduler_note;
    }
    if (g.memory_locked) {
      EXPECT_GT(locked_kb(), 0u);
    } else {
      EXPECT_FALSE(g.memory_note.empty());
    }
    if (g.cpu == 0) {
      cpu_set_t mine;
      pthread_getaffinity_np(pthread_self(), sizeof mine, &mine);
      EXPECT_EQ(CPU_COUNT(&mine), 1);
      EXPECT_TRUE(CPU_ISSET(0, &mine));
      if (cpus > 1) {
        EXPECT_FALSE(helper.may_run_on(0)) << "a helper thread was left on the haptic CPU";
      }
    } else {
      EXPECT_FALSE(g.cpu_note.empty());
    }
    if (helper_nice_before < 5) {  // a test run under `nice` starts its threads at or past 5
      EXPECT_GE(g.helper_threads_lowered, 1u);
      EXPECT_EQ(helper.nice(), 5);
    } else {
      EXPECT_EQ(helper.nice(), helper_nice_before);  // never raised
    }
  }
  EXPECT_EQ(policy_of_this_thread(), policy_before);
  EXPECT_EQ(helper.nice(), helper_nice_before);
  EXPECT_TRUE(helper.may_run_on(0));
  EXPECT_EQ(locked_kb(), 0u) << "memory still locked after the session";
}

TEST(RealtimeSession, PriorityZeroStaysOrdinary) {
  RealtimeOptions options;
  options.priority = 0;
  options.lock_memory = false;
  RealtimeSession session(options);
  EXPECT_EQ(session.grant().scheduler, "SCHED_OTHER");
  EXPECT_EQ(policy_of_this_thread(), SCHED_OTHER);
  EXPECT_NE(session.grant().scheduler_note.find("not requested"), std::string::npos);
  EXPECT_FALSE(session.grant().memory_locked);
}

// The haptic thread's sleeps end on time under SCHED_OTHER too: its timer slack (how late the
// kernel may end a sleep, 50 us by default, the whole spin window) is 1 ns for the run and back
// to what it was after.
TEST(RealtimeSession, TheHapticThreadSleepsWithoutTimerSlack) {
  const long slack_before = prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0);
  ASSERT_GT(slack_before, 1);
  {
    RealtimeOptions options;
    options.priority = 0;  // the SCHED_OTHER path, where slack applies
    options.lock_memory = false;
    RealtimeSession session(options);
    EXPECT_EQ(prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0), 1);
    EXPECT_EQ(session.grant().timer_slack_ns, 1u);
  }
  EXPECT_EQ(prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0), slack_before);
}

// How many descriptors this process holds open on /dev/cpu_dma_latency: each open one is a PM QoS
// request, and the kernel drops a request when its descriptor closes.
int latency_requests_held() {
  int held = 0;
  for (int fd = 0; fd < 1024; ++fd) {
    char link[64];
    char target[256];
    std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t n = readlink(link, target, sizeof target - 1);
    if (n <= 0) continue;
    target[n] = '\0';
    if (std::string(target) == "/dev/cpu_dma_latency") ++held;
  }
  return held;
}

// The PM QoS request: while the session holds it the kernel's effective CPU latency limit
// (what reading /dev/cpu_dma_latency returns) is 0 us; after, this process holds no request. The
// limit itself is not read after the session: any other process (a test running beside this one,
// tuned) may hold its own 0 us request, so only our descriptor says whether ours is gone.
TEST(RealtimeSession, HoldsCpusInShallowIdleStatesForTheRun) {
  const auto effective_us = []() -> long {
    std::ifstream in("/dev/cpu_dma_latency", std::ios::binary);
    int32_t value = -1;
    if (!in.read(reinterpret_cast<char*>(&value), sizeof value)) return -1;
    return value;
  };
  RealtimeOptions options;
  options.priority = 0;
  options.lock_memory = false;
  const int held_before = latency_requests_held();
  {
    RealtimeSession session(options);
    const tacta::RealtimeGrant& g = session.grant();
    if (!g.shallow_idle) {
      EXPECT_NE(g.idle_note.find("/dev/cpu_dma_latency"), std::string::npos) << g.idle_note;
      GTEST_SKIP() << g.idle_note;
    }
    EXPECT_TRUE(g.idle_note.empty());
    EXPECT_EQ(latency_requests_held(), held_before + 1);
    const long during = effective_us();
    if (during >= 0) {
      EXPECT_EQ(during, 0);
    }
  }
  EXPECT_EQ(latency_requests_held(), held_before) << "the request outlived the session";
  options.shallow_idle = false;
  RealtimeSession off(options);
  EXPECT_FALSE(off.grant().shallow_idle);
  EXPECT_EQ(off.grant().idle_note, "not requested (clock.shallow_idle: false)");
  EXPECT_EQ(latency_requests_held(), held_before);
}

// The threads of this process named `name` (/proc/self/task/*/comm).
std::vector<pid_t> threads_named(const std::string& name) {
  std::vector<pid_t> found;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream comm(task.path() / "comm");
    std::string line;
    if (std::getline(comm, line) && line == name)
      found.push_back(static_cast<pid_t>(std::stoi(task.path().filename().string())));
  }
  return found;
}

// clock.poll_idle: a pinned session runs one SCHED_IDLE thread on the haptic CPU (so it never
// idles, yet yields to any other thread at once), and it is gone when the session ends.
TEST(RealtimeSession, AnIdlePollerHoldsThePinnedCpuForTheRun) {
  RealtimeOptions options;
  options.priority = 0;
  options.lock_memory = false;
  options.cpu = 0;
  {
    RealtimeSession session(options);
    const tacta::RealtimeGrant& g = session.grant();
    if (g.cpu != 0) GTEST_SKIP() << "pinning refused here: " << g.cpu_note;
    ASSERT_TRUE(g.poll_idle) << g.poll_note;
    EXPECT_TRUE(g.poll_note.empty());
    const std::vector<pid_t> pollers = threads_named("tacta-idle-poll");
    ASSERT_EQ(pollers.size(), 1u);
    EXPECT_EQ(sched_getscheduler(pollers[0]), SCHED_IDLE);
    cpu_set_t cpus;
    ASSERT_EQ(sched_getaffinity(pollers[0], sizeof cpus, &cpus), 0);
    EXPECT_EQ(CPU_COUNT(&cpus), 1);
    EXPECT_TRUE(CPU_ISSET(0, &cpus));
  }
  EXPECT_TRUE(threads_named("tacta-idle-poll").empty()) << "the poller outlived the session";

  options.poll_idle = false;
  {
    RealtimeSession off(options);
    EXPECT_FALSE(off.grant().poll_idle);
    EXPECT_EQ(off.grant().poll_note, "not requested (clock.poll_idle: false)");
    EXPECT_TRUE(threads_named("tacta-idle-poll").empty());
  }
  options.poll_idle = true;
  options.cpu = -1;
  RealtimeSession unpinned(options);
  EXPECT_FALSE(unpinned.grant().poll_idle);
  EXPECT_NE(unpinned.grant().poll_note.find("not pinned"), std::string::npos);
  EXPECT_TRUE(threads_named("tacta-idle-poll").empty());
}

TEST(RealtimeSession, ResidentMemoryIsRead) {
  const tacta::ResidentMemory m = tacta::resident_memory();
  EXPECT_GT(m.rss_kb, 0u);
  EXPECT_GE(m.peak_kb, m.rss_kb);
}

}  // namespace
