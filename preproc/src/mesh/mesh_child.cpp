#include "mesh_child.hpp"

#include "ffr/formats/h5.hpp"  // FormatError

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace ffr::preproc::detail {
namespace {

// The child's answer, one of: 'M' mesh and report; 'F' a FormatError (file, object, detail);
// 'X' another error (its text). Plain bytes: both ends are the same executable.
class Writer {
 public:
  template <class T>
  void pod(const T& v) { buf_.append(reinterpret_cast<const char*>(&v), sizeof v); }
  void str(const std::string& s) {
    pod<std::uint64_t>(s.size());
    buf_.append(s);
  }
  template <class T>
  void vec(const T* p, std::size_t n) {
    pod<std::uint64_t>(n);
    buf_.append(reinterpret_cast<const char*>(p), n * sizeof(T));
  }
  const std::string& bytes() const { return buf_; }

 private:
  std::string buf_;
};

class Reader {
 public:
  explicit Reader(const std::string& b) : b_(b) {}
  template <class T>
  T pod() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  std::string str() {
    std::string s(count(1), '\0');
    take(s.data(), s.size());
    return s;
  }
  template <class T>
  std::vector<T> vec() {
    std::vector<T> v(count(sizeof(T)));
    take(v.data(), v.size() * sizeof(T));
    return v;
  }

 private:
  // A length that fits in what is left (so a damaged answer cannot ask for a huge allocation).
  std::size_t count(std::size_t elem) {
    const auto n = pod<std::uint64_t>();
    if (n > (b_.size() - pos_) / elem) throw std::runtime_error("the mesh from the gmsh process is incomplete");
    return static_cast<std::size_t>(n);
  }
  void take(void* p, std::size_t n) {
    if (n > b_.size() - pos_) throw std::runtime_error("the mesh from the gmsh process is incomplete");
    if (n) std::memcpy(p, b_.data() + pos_, n);
    pos_ += n;
  }
  const std::string& b_;
  std::size_t pos_ = 0;
};

std::string encode(const Mesh& m, const MeshReport& r) {
  Writer w;
  w.pod('M');
  w.pod<std::int64_t>(m.x.rows());
  w.vec(m.x.data(), static_cast<std::size_t>(m.x.size()));
  w.vec(m.node_tags.data(), m.node_tags.size());
  w.pod<std::uint64_t>(m.blocks.size());
  for (const ElementBlock& b : m.blocks) {
    w.pod<int>(static_cast<int>(b.type));
    w.str(b.group);
    w.vec(b.conn.data(), b.conn.size());
    w.vec(b.tags.data(), b.tags.size());
  }
  w.pod<std::uint64_t>(m.node_groups.size());
  for (const auto& [name, nodes] : m.node_groups) {
    w.str(name);
    w.vec(nodes.data(), nodes.size());
  }
  w.pod<std::uint64_t>(r.element_counts.size());
  for (const auto& [type, n] : r.element_counts) {
    w.str(type);
    w.pod<Index>(n);
  }
  w.pod<Index>(r.nodes);
  w.pod<double>(r.seconds);
  w.pod<char>(r.meshed ? 1 : 0);
  w.str(r.gmsh_log);
  return w.bytes();
}

Mesh decode(Reader& in, MeshReport* report) {
  Mesh m;
  const auto rows = in.pod<std::int64_t>();
  const auto x = in.vec<double>();
  if (rows < 0 || x.size() != 3 * static_cast<std::size_t>(rows)) throw std::runtime_error("the mesh from the gmsh process is inconsistent");
  m.x.resize(rows, 3);
  if (!x.empty()) std::memcpy(m.x.data(), x.data(), x.size() * sizeof(double));
  m.node_tags = in.vec<std::size_t>();
  for (auto nb = in.pod<std::uint64_t>(); nb > 0; --nb) {
    ElementBlock b;
    b.type = static_cast<ElementType>(in.pod<int>());
    b.group = in.str();
    b.conn = in.vec<Index>();
    b.tags = in.vec<std::size_t>();
    m.blocks.push_back(std::move(b));
  }
  for (auto ng = in.pod<std::uint64_t>(); ng > 0; --ng) {
    std::string name = in.str();
    m.node_groups[name] = in.vec<Index>();
  }
  MeshReport r;
  for (auto nc = in.pod<std::uint64_t>(); nc > 0; --nc) {
    std::string type = in.str();
    r.element_counts[type] = in.pod<Index>();
  }
  r.nodes = in.pod<Index>();
  r.seconds = in.pod<double>();
  r.meshed = in.pod<char>() != 0;
  r.gmsh_log = in.str();
  if (report) *report = std::move(r);
  return m;
}

void write_all(int fd, const std::string& s) {
  std::size_t done = 0;
  while (done < s.size()) {
    const ssize_t k = ::write(fd, s.data() + done, s.size() - done);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return;
    done += static_cast<std::size_t>(k);
  }
}

// The child while the parent has not collected it: killed and reaped on every way out of
// load_in_child (an exception included), so no gmsh process outlives the call.
class ChildGuard {
 public:
  explicit ChildGuard(pid_t pid) : pid_(pid) {}
  ChildGuard(const ChildGuard&) = delete;
  ChildGuard& operator=(const ChildGuard&) = delete;
  ~ChildGuard() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  /// Waits for the child's end until `deadline`; kills it then. Returns its status and whether
  /// it ended by itself.
  bool wait_until(std::chrono::steady_clock::time_point deadline, int& status) {
    for (;;) {
      const pid_t w = ::waitpid(pid_, &status, WNOHANG);
      if (w == pid_) {
        pid_ = -1;
        return true;
      }
      if (w < 0 && errno != EINTR) {  // not our child any more (cannot happen): nothing to reap
        pid_ = -1;
        status = 0;
        return true;
      }
      if (std::chrono::steady_clock::now() >= deadline) return false;
      ::usleep(2000);
    }
  }

 private:
  pid_t pid_;
};

// Seconds to milliseconds for poll(), at most a day per call.
int poll_ms(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
  return static_cast<int>(std::clamp<long long>(left, 0, 86400000LL));
}

}  // namespace

Mesh load_in_child(const std::string& file, const std::function<Mesh(MeshReport*)>& load, MeshReport* report,
                   const ChildLimit& limit) {
  int fd[2];
  if (::pipe2(fd, O_CLOEXEC) != 0) return load(report);
  std::fflush(nullptr);  // or the child's exit would write buffered output twice
  std::cout.flush();
  std::cerr.flush();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fd[0]);
    ::close(fd[1]);
    return load(report);
  }
  if (pid == 0) {
    // Die with the parent: a parent killed (kill -9 included) while gmsh meshes must not leave
    // gmsh running. The signal is tied to the parent's death only from here on, so a parent
    // that died between fork() and prctl() shows as a changed parent id: leave at once then.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(1);
    // A crash inside gmsh must end the child by its signal, which the parent reports as a file
    // gmsh cannot read (below). A handler the parent installed (AddressSanitizer's, in the
    // sanitizer build: it would print its report and exit with status 1) does not apply here.
    for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL}) ::signal(sig, SIG_DFL);
    ::close(fd[0]);
    std::string answer;
    try {
      MeshReport r;
      const Mesh m = load(&r);
      answer = encode(m, r);
    } catch (const formats::FormatError& e) {
      Writer w;
      w.pod('F');
      w.str(e.file());
      w.str(e.object());
      w.str(e.detail());
      answer = w.bytes();
    } catch (const std::exception& e) {
      Writer w;
      w.pod('X');
      w.str(e.what());
      answer = w.bytes();
    } catch (...) {
      Writer w;
      w.pod('X');
      w.str("unknown error while reading the mesh");
      answer = w.bytes();
    }
    write_all(fd[1], answer);
    ::close(fd[1]);
    std::fflush(nullptr);
    ::_exit(0);  // no destructors or atexit handlers of the parent's objects
  }
  ChildGuard child(pid);
  ::close(fd[1]);
  const auto start = std::chrono::steady_clock::now();
  const bool limited = limit.seconds > 0 && limit.seconds < 1e9;  // beyond: none (and no overflow of the clock)
  const auto deadline = limited ? start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                              std::chrono::duration<double>(limit.seconds))
                                : std::chrono::steady_clock::time_point::max();
  const auto too_slow = [&] {
    char secs[32];
    std::snprintf(secs, sizeof secs, "%g", limit.seconds);
    return formats::FormatError(file, "",
                                std::string("gmsh did not finish reading and meshing it within ") + secs + " s (" +
                                    limit.setting + "): a geometry script that does not end (a loop), or a mesh " +
                                    "too fine for the limit; check the script, give a larger mesh.size, or raise " +
                                    limit.setting);
  };
  std::string data;
  {
    struct Close {
      int fd;
      ~Close() { ::close(fd); }
    } reading{fd[0]};
    char buf[1 << 16];
    for (;;) {
      pollfd p{fd[0], POLLIN, 0};
      const int ready = ::poll(&p, 1, poll_ms(deadline));
      if (ready < 0 && errno == EINTR) continue;
      if (ready == 0) {
        if (std::chrono::steady_clock::now() >= deadline) throw too_slow();  // the guard kills gmsh
        continue;
      }
      if (ready < 0) break;
      const ssize_t k = ::read(fd[0], buf, sizeof buf);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0) break;
      data.append(buf, static_cast<std::size_t>(k));
    }
  }
  int status = 0;
  // The answer is complete; the child only exits now (a second is plenty, the limit aside).
  if (!child.wait_until(std::max(deadline, std::chrono::steady_clock::now() + std::chrono::seconds(1)), status))
    throw too_slow();
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    std::string what = std::string("gmsh crashed on this file (") + ::strsignal(sig) +
                       "): it is damaged or not a file gmsh can read";
    if (sig == SIGKILL) what += " (or the machine ran out of memory)";
    throw formats::FormatError(file, "", what);
  }
  if (data.empty()) throw std::runtime_error(file + ": the gmsh process ended without an answer");
  Reader in(data);
  const char kind = in.pod<char>();
  if (kind == 'F') {
    std::string f = in.str(), o = in.str(), d = in.str();
    throw formats::FormatError(std::move(f), std::move(o), d);
  }
  if (kind == 'X') throw std::runtime_error(in.str());
  if (kind != 'M') throw std::runtime_error(file + ": unexpected answer from the gmsh process");
  return decode(in, report);
}

}  // namespace ffr::preproc::detail
