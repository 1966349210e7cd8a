// Scheduling policy, memory locking and CPU placement around a realtime run (see realtime.hpp).
#include "tacta/sim/realtime.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <pthread.h>
#include <sched.h>
#include <string>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#include <vector>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TACTA_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define TACTA_SANITIZED 1
#endif
#endif

namespace tacta {

namespace {

#ifdef TACTA_SANITIZED
// A sanitizer's shadow memory is terabytes of reserved address space: mlockall would fault it in.
constexpr bool kCanLockMemory = false;
#else
constexpr bool kCanLockMemory = true;
#endif

// Helper threads (render, rasteriser, I/O) run this much nicer than the default 0; body worker
// threads keep their priority, their steps are simulation work with a deadline of their own.
constexpr int kHelperNice = 5;
// The fallback when SCHED_FIFO is refused: a nice value that still beats ordinary processes.
constexpr int kHapticFallbackNice = -10;

pid_t this_tid() { return static_cast<pid_t>(syscall(SYS_gettid)); }

std::string thread_name(pid_t tid) {
  std::ifstream in("/proc/self/task/" + std::to_string(tid) + "/comm");
  std::string name;
  std::getline(in, name);
  return name;
}

std::vector<pid_t> other_threads() {
  std::vector<pid_t> tids;
  DIR* dir = opendir("/proc/self/task");
  if (dir == nullptr) return tids;
  const pid_t self = this_tid();
  while (const dirent* entry = readdir(dir)) {
    const long tid = std::strtol(entry->d_name, nullptr, 10);
    if (tid > 0 && tid != self) tids.push_back(static_cast<pid_t>(tid));
  }
  closedir(dir);
  return tids;
}

std::string errno_text(int error) { return std::strerror(error); }

uint64_t status_kb(const std::string& text, const char* key) {
  const size_t at = text.find(key);
  return at == std::string::npos ? 0
                                 : std::strtoull(text.c_str() + at + std::strlen(key), nullptr, 10);
}

}  // namespace

ResidentMemory resident_memory() noexcept {
  ResidentMemory m;
  try {
    std::ifstream in("/proc/self/status");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    m.rss_kb = status_kb(text, "VmRSS:");
    m.peak_kb = status_kb(text, "VmHWM:");
  } catch (...) {
    // Reporting memory is best effort; a run never fails for it.
  }
  return m;
}

// The idle poller's body: it lowers itself to SCHED_IDLE (glibc's thread attributes cannot ask
// for it), says how that went in `state` (1 lowered, else -errno; it then ends), and spins on a
// relaxed load and a pause: the CPU stays out of its idle state, the haptic thread's cache lines
// are not touched.
void* poll_until_stopped(void* session_state) {
  auto* state = static_cast<std::atomic<int>*>(session_state);
  sched_param none{};
  if (sched_setscheduler(0, SCHED_IDLE, &none) != 0) {
    state->store(-errno);
    state->notify_one();
    return nullptr;
  }
  state->store(1);
  state->notify_one();
  while (state->load(std::memory_order_relaxed) == 1) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  return nullptr;
}

RealtimeSession::RealtimeSession(const RealtimeOptions& options) : options_(options) {
  char name[16] = {};
  pthread_getname_np(pthread_self(), name, sizeof name);
  old_name_ = name;
  pthread_setname_np(pthread_self(), "tacta-haptic");
  grant_.spin_us = options.spin_us;

  if (options.lock_memory && !kCanLockMemory) {
    grant_.memory_note = "not locked: a sanitizer build (its shadow memory cannot be locked)";
  } else if (options.lock_memory) {
    // Locks what is mapped and what will be: the record buffers reserved before the run are
    // faulted in now, not one page at a time inside ticks.
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0)
      grant_.memory_locked = true;
    else
      grant_.memory_note = "mlockall refused (" + errno_text(errno) +
                           "); raise RLIMIT_MEMLOCK (ulimit -l) or grant CAP_IPC_LOCK";
  } else {
    grant_.memory_note = "not requested (clock.lock_memory: false)";
  }

  if (options.shallow_idle) {
    // The request holds while the file stays open (kernel PM QoS); closing it drops it.
    latency_fd_ = open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
    const int32_t zero_us = 0;
    if (latency_fd_ >= 0 && write(latency_fd_, &zero_us, sizeof zero_us) == sizeof zero_us) {
      grant_.shallow_idle = true;
    } else {
      grant_.idle_note = "/dev/cpu_dma_latency refused (" + errno_text(errno) +
                         "); deep idle states stay allowed (needs root, or write access to it)";
      if (latency_fd_ >= 0) close(latency_fd_);
      latency_fd_ = -1;
    }
  } else {
    grant_.idle_note = "not requested (clock.shallow_idle: false)";
  }

  sched_param old{};
  pthread_getschedparam(pthread_self(), &old_policy_, &old);
  old_priority_ = old.sched_priority;
  errno = 0;
  old_nice_ = getpriority(PRIO_PROCESS, static_cast<id_t>(this_tid()));
  if (options.priority > 0) {
    sched_param wanted{};
    wanted.sched_priority = options.priority;
    const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &wanted);
    if (error == 0) {
      grant_.scheduler = "SCHED_FIFO";
      grant_.priority = options.priority;
    } else {
      grant_.scheduler_note =
          "SCHED_FIFO " + std::to_string(options.priority) + " refused (" + errno_text(error) +
          "; needs CAP_SYS_NICE or an RLIMIT_RTPRIO, e.g. in /etc/security/limits.conf)";
    }
  } else {
    grant_.scheduler_note = "SCHED_FIFO not requested (clock.haptic_priority: 0)";
  }
  if (grant_.scheduler != "SCHED_FIFO") {
    if (setpriority(PRIO_PROCESS, static_cast<id_t>(this_tid()), kHapticFallbackNice) == 0) {
      grant_.nice = kHapticFallbackNice;
      grant_.scheduler_note +=
          "; fallback: SCHED_OTHER at nice " + std::to_string(kHapticFallbackNice);
    } else {
      grant_.nice = old_nice_;
      grant_.scheduler_note += "; fallback: SCHED_OTHER at nice " + std::to_string(old_nice_) +
                               " (raising it was refused too)";
    }
  }

  // A SCHED_OTHER thread's sleeps may end up to its timer slack late, 50 us by default: the
  // whole spin window, so every wait would wake past its deadline. SCHED_FIFO threads get no
  // slack from the kernel; 1 ns gives the fallback (and a demoted thread) the same.
  old_timer_slack_ns_ = prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0);
  if (prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0) == 0)
    grant_.timer_slack_ns = 1;
  else if (old_timer_slack_ns_ > 0)
    grant_.timer_slack_ns = static_cast<uint64_t>(old_timer_slack_ns_);

  if (options.cpu >= 0) {
    cpu_set_t original;
    CPU_ZERO(&original);
    pthread_getaffinity_np(pthread_self(), sizeof original, &original);
    for (int c = 0; c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &original)) original_cpus_.push_back(c);
    cpu_set_t only;
    CPU_ZERO(&only);
    CPU_SET(options.cpu, &only);
    const int error = options.cpu < CPU_SETSIZE
                          ? pthread_setaffinity_np(pthread_self(), sizeof only, &only)
                          : EINVAL;
    if (error == 0) {
      grant_.cpu = options.cpu;
    } else {
      grant_.cpu_note =
          "pinning to CPU " + std::to_string(options.cpu) + " refused (" + errno_text(error) + ")";
    }
  }
  for (const pid_t tid : other_threads()) {
    if (thread_name(tid).rfind("tacta-body", 0) == 0) {
      // Body workers keep their priority but still leave the haptic CPU to the haptic thread.
      if (grant_.cpu >= 0) {
        cpu_set_t rest;
        sched_getaffinity(tid, sizeof rest, &rest);
        CPU_CLR(grant_.cpu, &rest);
        if (CPU_COUNT(&rest) > 0) sched_setaffinity(tid, sizeof rest, &rest);
      }
      continue;
    }
    cpu_set_t rest;
    if (grant_.cpu >= 0 && sched_getaffinity(tid, sizeof rest, &rest) == 0) {
      CPU_CLR(grant_.cpu, &rest);
      if (CPU_COUNT(&rest) > 0) sched_setaffinity(tid, sizeof rest, &rest);
    }
    errno = 0;
    const int nice = getpriority(PRIO_PROCESS, static_cast<id_t>(tid));
    if (errno == 0 && nice < kHelperNice &&
        setpriority(PRIO_PROCESS, static_cast<id_t>(tid), kHelperNice) == 0) {
      lowered_.push_back({tid, nice});
      ++grant_.helper_threads_lowered;
    }
  }
  if (!options.poll_idle) {
    grant_.poll_note = "not requested (clock.poll_idle: false)";
  } else if (grant_.cpu < 0) {
    grant_.poll_note = "not pinned (clock.haptic_cpu): no CPU of the haptic thread's own to hold";
  } else {
    start_idle_poller();
  }
}

void RealtimeSession::start_idle_poller() {
  // Born SCHED_OTHER on the haptic CPU (not inheriting the haptic thread's SCHED_FIFO, which
  // would hold the CPU against it), then lowered by itself; the wait below sleeps, so the
  // haptic thread leaves it the CPU to do that.
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED);
  pthread_attr_setschedpolicy(&attr, SCHED_OTHER);
  sched_param none{};
  pthread_attr_setschedparam(&attr, &none);
  cpu_set_t only;
  CPU_ZERO(&only);
  CPU_SET(grant_.cpu, &only);
  pthread_attr_setaffinity_np(&attr, sizeof only, &only);
  const int error = pthread_create(&idle_poller_, &attr, poll_until_stopped, &poller_state_);
  pthread_attr_destroy(&attr);
  if (error != 0) {
    grant_.poll_note = "the idle poller was refused (" + errno_text(error) + ")";
    return;
  }
  pthread_setname_np(idle_poller_, "tacta-idle-poll");
  poller_state_.wait(0);
  if (poller_state_.load() == 1) {
    polling_ = grant_.poll_idle = true;
  } else {
    pthread_join(idle_poller_, nullptr);
    grant_.poll_note =
        "SCHED_IDLE refused to the idle poller (" + errno_text(-poller_state_.load()) + ")";
  }
}

void RealtimeSession::lower_this_thread() noexcept {
  const pid_t tid = this_tid();
  if (grant_.cpu >= 0) {
    cpu_set_t rest;
    if (sched_getaffinity(tid, sizeof rest, &rest) == 0) {
      CPU_CLR(grant_.cpu, &rest);
      if (CPU_COUNT(&rest) > 0) sched_setaffinity(tid, sizeof rest, &rest);
    }
  }
  setpriority(PRIO_PROCESS, static_cast<id_t>(tid), kHelperNice);
}

bool RealtimeSession::demote(int64_t tick) noexcept {
  if (grant_.scheduler != "SCHED_FIFO") return false;
  sched_param normal{};
  if (pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal) != 0) return false;
  const bool niced =
      setpriority(PRIO_PROCESS, static_cast<id_t>(this_tid()), kHapticFallbackNice) == 0;
  grant_.demoted_at_tick = tick;
  grant_.nice = niced ? kHapticFallbackNice : old_nice_;
  return true;
}

RealtimeSession::~RealtimeSession() {
  if (polling_) {
    poller_state_.store(0, std::memory_order_relaxed);
    pthread_join(idle_poller_, nullptr);
  }
  sched_param old{};
  old.sched_priority = old_priority_;
  pthread_setschedparam(pthread_self(), old_policy_, &old);
  setpriority(PRIO_PROCESS, static_cast<id_t>(this_tid()), old_nice_);
  if (old_timer_slack_ns_ > 0)
    prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(old_timer_slack_ns_), 0, 0, 0);
  pthread_setname_np(pthread_self(), old_name_.c_str());
  for (const LoweredThread& t : lowered_)
    setpriority(PRIO_PROCESS, static_cast<id_t>(t.tid), t.nice);
  if (!original_cpus_.empty()) {
    // Every thread may use the CPUs the haptic thread had before the run again.
    cpu_set_t all;
    CPU_ZERO(&all);
    for (const int c : original_cpus_) CPU_SET(c, &all);
    pthread_setaffinity_np(pthread_self(), sizeof all, &all);
    for (const pid_t tid : other_threads()) sched_setaffinity(tid, sizeof all, &all);
  }
  if (grant_.memory_locked) munlockall();
  if (latency_fd_ >= 0) close(latency_fd_);
}

}  // namespace tacta
