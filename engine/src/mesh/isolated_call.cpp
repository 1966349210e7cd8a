// call_isolated: fork, run, send the bytes back through a pipe (see isolated_call.hpp).
#include "mesh/isolated_call.hpp"

#include <cerrno>
#include <chrono>
#include <exception>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tacta/error.hpp"

namespace tacta::mesh_detail {

namespace {

void write_all(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

// The child: 'K' and the result, or 'E' and the error message; never returns.
[[noreturn]] void run_child(int fd, const std::function<std::string()>& work) {
  std::string reply;
  try {
    reply = "K" + work();
  } catch (const std::exception& e) {
    reply = std::string("E") + e.what();
  } catch (...) {
    reply = "Eunknown failure";
  }
  write_all(fd, reply);
  ::close(fd);
  ::_exit(0);  // no atexit handlers, no static destructors of the parent's copy
}

}  // namespace

std::string call_isolated(const std::function<std::string()>& work, const std::string& source,
                          double timeout_s) {
  int fds[2];
  if (::pipe(fds) != 0) throw InputError({source, 0, 0, ""}, "cannot start the mesher: no pipe");
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw InputError({source, 0, 0, ""}, "cannot start the mesher: fork failed");
  }
  if (child == 0) {
    ::close(fds[0]);
    run_child(fds[1], work);
  }
  ::close(fds[1]);
  std::string reply;
  char buffer[1 << 16];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;  // the deadline is checked above
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child is done
    reply.append(buffer, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out)
    throw InputError({source, 0, 0, ""}, "the mesher ran past " +
                                             std::to_string(static_cast<int>(timeout_s)) +
                                             " s and was stopped");
  if (WIFSIGNALED(status)) {
    throw InputError({source, 0, 0, ""}, "the mesher crashed (signal " +
                                             std::to_string(WTERMSIG(status)) + ") on this input");
  }
  if (reply.empty()) throw InputError({source, 0, 0, ""}, "the mesher stopped without an answer");
  if (reply[0] == 'E') throw InputError({source, 0, 0, ""}, reply.substr(1));
  return reply.substr(1);
}

}  // namespace tacta::mesh_detail
