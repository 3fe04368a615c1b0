// files: a run's dealings with the file system and with other programs, without a shell (built by
// `make` with ff-c++; loaded by include/core/run.idp). A path goes to the system calls as it is:
// nothing a user types is spliced into a command line, so a quote, a blank or a leading '-' in a
// path is only a character of a name.
//
// The output folder. A run locks it, then removes what earlier runs wrote there, then writes its
// own files. A file counts as the suite's only by its identity (device, inode and birth time where
// the file system keeps one), recorded in <folder>/.outputs when the file is created: never by its
// name alone, so a user's file under an output's name, the lock, an input of the run or anything
// outside the folder is never removed or written, whatever .outputs says. Every output is created
// fresh (a new file under a temporary name, renamed into place), so nothing is written through a
// symbolic or a hard link planted at its name; later writes go into that file only after its
// identity is checked again.
//
//   pathKind(path): 0 nothing there, 1 a regular file, 2 a directory, 3 a symbolic link, 4 else
//     (lstat: a link is not followed).
//   fileBytes(path): its size in bytes (a link followed), -1 when it cannot be read.
//   fileEndsWith(path, text): 1 when the file's last bytes are text (trailing white space ignored): how
//     a file written by a writer that reports no error (FreeFEM's savevtk) is known to be whole.
//   makeFolder(path): creates the folder and its missing parents (mkdir -p); 0, or the errno.
//   lockFolder(folder): an exclusive lock on folder/.lock (flock), held until the process ends, on
//     a descriptor closed on exec (a child such as gmsh does not keep the folder locked): 0, 1 when
//     another process holds it, ENXIO when .lock is not a regular file, or the errno. The folder is
//     then the run's output folder: the only one the functions below create files in.
//   writeProbe(folder): creates and removes folder/.write_probe (after lockFolder: an empty one
//     left by a killed run is removed first); 0, EEXIST when something else has that name, or the
//     errno.
//   cleanOutputs(folder): removes the files recorded in folder/.outputs ("dev ino birth name"
//     lines) whose identity still matches (and their temporary names), except the run's inputs,
//     whose records are kept; then starts a new .outputs. Returns how many it removed; -1 when
//     .outputs cannot be read, -2 when it is not a regular file (a link, a FIFO, a device, a
//     folder), -3 when it is larger than any list the suite writes, -4 when the new one cannot be
//     created.
//   outputObstacle(folder, names, patterns): the first entry of the folder, among the exact names
//     and the glob patterns given (one a line), that a run could not replace: "name\tfile" (a file
//     the suite did not write), "name\tfolder" or "name\tspecial" (a FIFO, device or socket); ""
//     when there is none. Links (symbolic or hard) are replaced when written, inputs never are.
//   claimOutput(path): makes path, a plain name in the output folder, hold an empty file of this
//     run's (created fresh and recorded, or this run's own already): 0; EEXIST when a file the
//     suite did not write is there, EISDIR a folder, ENXIO a special file, EBUSY one of the run's
//     inputs, EXDEV a path outside the output folder; or the errno.
//   writeTextFile(path, text), appendTextFile(path, text): text into the output (claimed first),
//     replacing its content or at its end, each step checked (open, identity, write, close; fsync
//     for a whole file): 0, or the errno (ENOSPC on a full disk). FreeFEM's ofstream reports no
//     error.
//   replaceTextFile(path, text): text into a fresh file, synced, then renamed over path: the output
//     is whole or absent (summary.json). 0, or the claim's codes or the errno.
//   completeLines(path): the number of lines of a text file that ends with a newline (every file the
//     suite writes does); -1 when the file cannot be read, -2 when its last line has no newline. A
//     write cut short (a full disk: the stream's buffered tail lost) leaves fewer lines or no final
//     newline: how the scripts check their writes, FreeFEM's ofstream reporting no error.
//   runProgram(program, arguments, log): runs program with its arguments (one per line of
//     `arguments`) by fork and execvp, no shell, standard output and error into the output `log`,
//     in a process group of its own, killed if this process dies (PR_SET_PDEATHSIG); returns its
//     exit status, 127 when it could not be started, 128 + n when signal n ended it.
//   inputProblem(path): why a file given as input (-mesh, -splinefile) cannot be read ("" when it
//     can): missing, a folder, a FIFO, device or socket (which would block or never end),
//     unreadable. A readable one is recorded as an input: never removed nor written by the run.
//   errorText(code): strerror(code).
//   pathProblem(path): why a path given on the command line is refused ("" when it is not): empty, a
//     control character, a quote or a backslash, a leading '-'. Such names are more likely a mistake
//     or an attack than a choice, and a control character would break the files that quote paths
//     (IPOPT's options file, summary.json).
//   jsonText(text): text as a JSON string, quotes, backslashes and control characters escaped.
//   realText(x): x with the fewest significant digits (15 to 17) that read back as x (FreeFEM's
//     "" + x keeps 6).
//   privateTextFile(text): a path at which the process, and only it, reads text: an anonymous
//     file in memory (memfd_create), nothing on any disk; the one file is rewritten at each call.
//     IPOPT's options for the processes of an MPI run other than 0, which write nothing.
// Under MPI (FreeFem++-mpi) only process 0 writes: on the others, every call above that would
// change the file system (makeFolder, lockFolder, writeProbe, cleanOutputs, claimOutput,
// writeTextFile, appendTextFile, replaceTextFile, runProgram) does nothing and returns success.
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <map>
#include <string>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern long mpirank;   // FreeFEM's: 0 under FreeFem++

namespace {

bool writesHere() { return mpirank == 0; }

// What a file is, whatever its name: a name removed and made again (ext4 reuses inode numbers at
// once) differs in its birth time.
struct Identity {
  unsigned long long dev = 0, ino = 0;
  long long birthSeconds = 0, birthNanoseconds = 0;
  bool operator==(const Identity &o) const {
    return dev == o.dev && ino == o.ino && birthSeconds == o.birthSeconds
           && birthNanoseconds == o.birthNanoseconds;
  }
};

// statx of an open descriptor (path "") or of a path, links not followed; the kind and link count
// in `mode` and `links`. False when it fails (errno set).
bool identityOf(int fd, const std::string &path, Identity &id, unsigned &mode, unsigned &links) {
  struct statx sx;
  int flags = fd >= 0 ? AT_EMPTY_PATH : AT_SYMLINK_NOFOLLOW;
  if (statx(fd >= 0 ? fd : AT_FDCWD, fd >= 0 ? "" : path.c_str(), flags,
            STATX_BASIC_STATS | STATX_BTIME, &sx) != 0)
    return false;
  id.dev = makedev(sx.stx_dev_major, sx.stx_dev_minor);
  id.ino = sx.stx_ino;
  bool born = sx.stx_mask & STATX_BTIME;
  id.birthSeconds = born ? sx.stx_btime.tv_sec : 0;
  id.birthNanoseconds = born ? sx.stx_btime.tv_nsec : 0;
  mode = sx.stx_mode;
  links = sx.stx_nlink;
  return true;
}

bool plainName(const std::string &name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos
         && name.find('\n') == std::string::npos;
}

// The suite's own files in the folder: never outputs, never removed through .outputs.
bool reservedName(const std::string &name) {
  return name == ".lock" || name == ".outputs" || name == ".write_probe";
}

std::string temporaryName(const std::string &folder, const std::string &name) {
  return folder + "/." + name + ".new";
}

std::string outputFolder;                  // set by lockFolder
int outputList = -1;                       // the new .outputs, open for appending (cleanOutputs)
std::map<std::string, Identity> owned;     // the outputs this run created, by path
std::vector<Identity> inputs;              // the run's input files (inputProblem)

bool isInput(const Identity &id) {
  for (auto &in : inputs)
    if (in.dev == id.dev && in.ino == id.ino) return true;
  return false;
}

long writeAll(int fd, const std::string &text) {
  size_t done = 0;
  while (done < text.size()) {
    ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    done += size_t(n);
  }
  return 0;
}

std::string recordLine(const Identity &id, const std::string &name) {
  char head[96];
  snprintf(head, sizeof head, "%llu %llu %lld.%09lld ", id.dev, id.ino, id.birthSeconds,
           id.birthNanoseconds);
  return head + name + "\n";
}

long pathKind(string *const &path) {
  struct stat info;
  if (lstat(path->c_str(), &info) != 0) return 0;
  if (S_ISREG(info.st_mode)) return 1;
  if (S_ISDIR(info.st_mode)) return 2;
  if (S_ISLNK(info.st_mode)) return 3;
  return 4;
}

long fileBytes(string *const &path) {
  struct stat info;
  if (stat(path->c_str(), &info) != 0) return -1;
  return long(info.st_size);
}

long fileEndsWith(string *const &path, string *const &text) {
  FILE *f = fopen(path->c_str(), "rb");
  if (!f) return 0;
  std::string tail(text->size() + 64, '\0');
  long size = 0;
  if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
  long start = std::max(0L, size - long(tail.size()));
  size_t got = (fseek(f, start, SEEK_SET) == 0) ? fread(&tail[0], 1, tail.size(), f) : 0;
  fclose(f);
  tail.resize(got);
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == ' ' || tail.back() == '\r'))
    tail.pop_back();
  return tail.size() >= text->size()
         && tail.compare(tail.size() - text->size(), text->size(), *text) == 0;
}

long makeFolder(string *const &path) {
  if (!writesHere()) return 0;
  const std::string &p = *path;
  if (p.empty()) return ENOENT;
  for (size_t i = 1; i <= p.size(); i++) {
    if (i < p.size() && p[i] != '/') continue;
    std::string prefix = p.substr(0, i);
    if (mkdir(prefix.c_str(), 0777) != 0 && errno != EEXIST) return errno;
  }
  struct stat info;
  if (stat(p.c_str(), &info) != 0) return errno;
  return S_ISDIR(info.st_mode) ? 0 : ENOTDIR;
}

int heldLock = -1;   // kept open for the process's life: the lock goes with it
long lockFolder(string *const &folder) {
  if (!writesHere()) return 0;
  std::string file = *folder + "/.lock";
  int fd = open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd < 0) return errno == ELOOP ? ENXIO : errno;
  struct stat info;
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd);
    return ENXIO;
  }
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    int error = errno;
    close(fd);
    return error == EWOULDBLOCK ? 1 : error;
  }
  if (heldLock >= 0) close(heldLock);
  heldLock = fd;
  outputFolder = *folder;
  return 0;
}

long writeProbe(string *const &folder) {
  if (!writesHere()) return 0;
  std::string probe = *folder + "/.write_probe";
  struct stat info;
  if (lstat(probe.c_str(), &info) == 0) {
    // a killed run's probe: empty, and no other run can be writing it while we hold the lock
    bool stale = S_ISLNK(info.st_mode)
                 || (S_ISREG(info.st_mode) && info.st_size == 0 && info.st_nlink == 1);
    if (!stale || heldLock < 0 || *folder != outputFolder) return EEXIST;
    if (unlink(probe.c_str()) != 0) return errno;
  }
  int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  close(fd);
  unlink(probe.c_str());
  return 0;
}

// The lines of .outputs as records: false for a line that is not one (older lists held names only:
// a name alone proves nothing, such lines are ignored).
bool parseRecord(const std::string &line, Identity &id, std::string &name) {
  unsigned long long dev, ino;
  long long seconds, fraction = 0;
  int used = 0;
  if (sscanf(line.c_str(), "%llu %llu %lld%n", &dev, &ino, &seconds, &used) != 3) return false;
  size_t at = size_t(used);
  if (at < line.size() && line[at] == '.') {
    int more = 0;
    if (sscanf(line.c_str() + at + 1, "%lld%n", &fraction, &more) != 1) return false;
    at += 1 + size_t(more);
  }
  if (at >= line.size() || line[at] != ' ') return false;
  name = line.substr(at + 1);
  id.dev = dev;
  id.ino = ino;
  id.birthSeconds = seconds;
  id.birthNanoseconds = fraction;
  return plainName(name) && !reservedName(name);
}

const off_t largestList = 64 << 20;   // 64 MB: a million records
long lastListError = 0;

long cleanOutputs(string *const &folder) {
  if (!writesHere()) return 0;
  std::string list = *folder + "/.outputs";
  std::string text;
  struct stat info;
  bool present = lstat(list.c_str(), &info) == 0;
  if (present) {
    if (!S_ISREG(info.st_mode)) return -2;   // a FIFO or /dev/zero would block or never end
    int fd = open(list.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) { lastListError = errno; return -1; }
    if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) { close(fd); return -2; }
    if (info.st_size > largestList) { close(fd); return -3; }
    text.resize(size_t(info.st_size));
    size_t got = 0;
    while (got < text.size()) {
      ssize_t n = read(fd, &text[got], text.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += size_t(n);
    }
    close(fd);
    text.resize(got);
  } else if (errno != ENOENT) {
    lastListError = errno;
    return -1;
  }
  long removed = 0;
  std::string kept;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start), name;
    start = end + 1;
    Identity recorded;
    if (!parseRecord(line, recorded, name)) continue;
    for (const std::string &path : {*folder + "/" + name, temporaryName(*folder, name)}) {
      Identity id;
      unsigned mode, links;
      if (!identityOf(-1, path, id, mode, links) || !S_ISREG(mode) || !(id == recorded)) continue;
      if (isInput(id)) kept += line + "\n";   // read by this run: it stays, still recorded
      else if (unlink(path.c_str()) == 0) removed++;
    }
  }
  if (present && unlink(list.c_str()) != 0 && errno != ENOENT) { lastListError = errno; return -4; }
  int flags = O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_APPEND | O_CLOEXEC;
  int fd = open(list.c_str(), flags, 0644);
  if (fd < 0) { lastListError = errno; return -4; }
  if (long error = writeAll(fd, kept)) { lastListError = error; close(fd); return -4; }
  if (outputList >= 0) close(outputList);
  outputList = fd;
  return removed;
}

long listError() { return lastListError; }

// What lies at path, for a run about to write there: 0 nothing, a link or a hard link (to be
// replaced), 1 this run's own file (to be reused), or the claim's error codes.
long targetState(const std::string &path, bool &ours) {
  ours = false;
  Identity id;
  unsigned mode, links;
  if (!identityOf(-1, path, id, mode, links)) return errno == ENOENT ? 0 : errno;
  if (S_ISDIR(mode)) return EISDIR;
  if (S_ISLNK(mode)) return 0;
  if (!S_ISREG(mode)) return ENXIO;
  if (isInput(id)) return EBUSY;
  auto it = owned.find(path);
  if (it != owned.end() && it->second == id && links == 1) ours = true;
  else if (links == 1) return EEXIST;   // a file the suite did not write: left alone
  return 0;
}

// path within the output folder, as a plain name: its name, or "" when it is not.
std::string nameInFolder(const std::string &path) {
  size_t slash = path.rfind('/');
  if (slash == std::string::npos || outputFolder.empty() || path.substr(0, slash) != outputFolder)
    return "";
  std::string name = path.substr(slash + 1);
  return plainName(name) && !reservedName(name) ? name : "";
}

// A fresh file holding text, recorded in .outputs and renamed over path.
long createFresh(const std::string &path, const std::string &name, const std::string &text,
                 bool sync) {
  if (outputList < 0) return EBADF;
  std::string temporary = temporaryName(outputFolder, name);
  int fd = open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  Identity id;
  unsigned mode, links;
  long error = identityOf(fd, "", id, mode, links) ? 0 : errno;
  if (!error) error = writeAll(outputList, recordLine(id, name));
  if (!error) error = writeAll(fd, text);
  // (fsync is not meaningful on every file system: EINVAL, EROFS are not failures)
  if (!error && sync && fsync(fd) != 0 && errno != EINVAL && errno != EROFS) error = errno;
  if (close(fd) != 0 && !error) error = errno;
  if (!error && rename(temporary.c_str(), path.c_str()) != 0) error = errno;
  if (error) {
    unlink(temporary.c_str());
    return error;
  }
  owned[path] = id;
  return 0;
}

long claim(const std::string &path) {
  std::string name = nameInFolder(path);
  if (name.empty()) return EXDEV;
  bool ours;
  long state = targetState(path, ours);
  if (state != 0 || ours) return state;
  return createFresh(path, name, "", false);
}

long claimOutput(string *const &path) {
  if (!writesHere()) return 0;
  return claim(*path);
}

// text into this run's own output at path (claimed first): its content replaced, or appended
long writeText(const std::string &path, const std::string &text, bool append) {
  if (!writesHere()) return 0;
  if (long error = claim(path)) return error;
  int flags = O_WRONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | (append ? O_APPEND : 0);
  int fd = open(path.c_str(), flags);
  if (fd < 0) return errno;
  Identity id;
  unsigned mode, links;
  long error = identityOf(fd, "", id, mode, links) ? 0 : errno;
  if (!error && !(id == owned[path] && links == 1)) error = EEXIST;   // replaced since the claim
  if (!error && !append && ftruncate(fd, 0) != 0) error = errno;
  if (!error) error = writeAll(fd, text);
  // a whole file is synced (a file system may report a lost write only then); an appended line is
  // not (thousands of syncs for a pressure.csv): its write and close report a full disk (ext4
  // reserves the blocks of a buffered write at write time, tmpfs allocates them then)
  if (!error && !append && fsync(fd) != 0 && errno != EINVAL && errno != EROFS) error = errno;
  if (close(fd) != 0 && !error) error = errno;
  return error;
}
long writeTextFile(string *const &path, string *const &text) {
  return writeText(*path, *text, false);
}
long appendTextFile(string *const &path, string *const &text) {
  return writeText(*path, *text, true);
}

long replaceTextFile(string *const &path, string *const &text) {
  if (!writesHere()) return 0;
  std::string name = nameInFolder(*path);
  if (name.empty()) return EXDEV;
  bool ours;
  if (long state = targetState(*path, ours)) return state;
  return createFresh(*path, name, *text, true);
}

string *outputObstacle(Stack s, string *const &folder, string *const &names,
                       string *const &patterns) {
  std::string found;
  DIR *dir = writesHere() ? opendir(folder->c_str()) : nullptr;
  while (dir && found.empty()) {
    struct dirent *entry = readdir(dir);
    if (!entry) break;
    std::string name = entry->d_name;
    bool listed = ("\n" + *names + "\n").find("\n" + name + "\n") != std::string::npos;
    for (size_t start = 0; !listed && start < patterns->size();) {
      size_t end = patterns->find('\n', start);
      if (end == std::string::npos) end = patterns->size();
      listed = fnmatch(patterns->substr(start, end - start).c_str(), name.c_str(), 0) == 0;
      start = end + 1;
    }
    if (!listed || !plainName(name)) continue;
    bool ours;
    long state = targetState(*folder + "/" + name, ours);
    if (state == EEXIST) found = name + "\tfile";
    else if (state == EISDIR) found = name + "\tfolder";
    else if (state == ENXIO) found = name + "\tspecial";
  }
  if (dir) closedir(dir);
  return Add2StackOfPtr2Free(s, new string(found));
}

string *inputProblem(Stack s, string *const &path) {
  std::string why;
  struct stat info;
  if (stat(path->c_str(), &info) != 0) why = errno == ENOENT ? "does not exist" : strerror(errno);
  else if (S_ISDIR(info.st_mode)) why = "is a folder, not a file";
  else if (!S_ISREG(info.st_mode)) why = "is a FIFO, a device or a socket, not a regular file";
  else {
    int fd = open(path->c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) why = std::string("cannot be read (") + strerror(errno) + ")";
    else {
      Identity id;
      unsigned mode, links;
      if (!identityOf(fd, "", id, mode, links) || !S_ISREG(mode)) why = "is not a regular file";
      else inputs.push_back(id);
      close(fd);
    }
  }
  return Add2StackOfPtr2Free(s, new string(why));
}

long completeLines(string *const &path) {
  FILE *f = fopen(path->c_str(), "rb");
  if (!f) return -1;
  long lines = 0;
  int c, last = '\n';
  while ((c = fgetc(f)) != EOF) {
    if (c == '\n') lines++;
    last = c;
  }
  bool failed = ferror(f) != 0;
  fclose(f);
  if (failed) return -1;
  return last == '\n' ? lines : -2;
}

long runProgram(string *const &program, string *const &arguments, string *const &log) {
  if (!writesHere()) return 0;
  if (claim(*log) != 0) return 127;
  std::vector<std::string> words;
  words.push_back(*program);
  size_t start = 0;
  const std::string &a = *arguments;
  while (start < a.size()) {
    size_t end = a.find('\n', start);
    if (end == std::string::npos) end = a.size();
    words.push_back(a.substr(start, end - start));
    start = end + 1;
  }
  std::vector<char *> argv;
  for (auto &w : words) argv.push_back(const_cast<char *>(w.c_str()));
  argv.push_back(nullptr);
  fflush(stdout);
  fflush(stderr);
  pid_t parent = getpid();
  pid_t pid = fork();
  if (pid < 0) return 127;
  if (pid == 0) {
    // its own process group, and killed with its parent: a run killed while meshing leaves no gmsh
    // writing a mesh into a folder nobody holds any more
    setpgid(0, 0);
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent) _exit(127);
    int fd = open(log->c_str(), O_WRONLY | O_TRUNC | O_NOFOLLOW);
    if (fd < 0) _exit(127);
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) { dup2(devnull, 0); close(devnull); }
    execvp(argv[0], argv.data());
    _exit(127);
  }
  setpgid(pid, pid);   // (both sides: whichever runs first)
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 127;
}

string *privateTextFile(Stack s, string *const &text) {
  static int descriptor = -1;
  if (descriptor < 0) descriptor = memfd_create("private_text", MFD_CLOEXEC);
  bool written = descriptor >= 0 && ftruncate(descriptor, 0) == 0 && lseek(descriptor, 0, SEEK_SET) == 0;
  for (size_t done = 0; written && done < text->size();) {
    ssize_t n = write(descriptor, text->data() + done, text->size() - done);
    if (n <= 0) written = false; else done += size_t(n);
  }
  ffassert(written);   // memory, not a disk: only an exhausted process fails here
  return Add2StackOfPtr2Free(s, new string("/proc/self/fd/" + std::to_string(descriptor)));
}

string *errorText(Stack s, const long &code) { return Add2StackOfPtr2Free(s, new string(strerror(int(code)))); }

string *pathProblem(Stack s, string *const &path) {
  const std::string &p = *path;
  std::string why;
  if (p.empty()) why = "is empty";
  else if (p[0] == '-') why = "starts with '-'";
  for (unsigned char c : p) {
    if (!why.empty()) break;
    if (c < 0x20 || c == 0x7f) why = "contains a control character";
    else if (c == '\'' || c == '"' || c == '`' || c == '\\') why = "contains a quote or a backslash";
  }
  return Add2StackOfPtr2Free(s, new string(why));
}

string *jsonText(Stack s, string *const &text) {
  std::string quoted = "\"";
  for (unsigned char c : *text) {
    if (c == '"' || c == '\\') { quoted += '\\'; quoted += char(c); }
    else if (c == '\n') quoted += "\\n";
    else if (c == '\t') quoted += "\\t";
    else if (c < 0x20 || c == 0x7f) { char code[8]; snprintf(code, sizeof code, "\\u%04x", c); quoted += code; }
    else quoted += char(c);
  }
  quoted += '"';
  return Add2StackOfPtr2Free(s, new string(quoted));
}

string *realText(Stack s, const double &x) {
  char buffer[64];
  for (int digits = 15; digits <= 17; digits++) {   // the shortest that reads back as x
    snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (strtod(buffer, nullptr) == x) break;
  }
  return Add2StackOfPtr2Free(s, new string(buffer));
}

void init() {
  Global.Add("pathKind", "(", new OneOperator1_<long, string *>(pathKind));
  Global.Add("fileBytes", "(", new OneOperator1_<long, string *>(fileBytes));
  Global.Add("fileEndsWith", "(", new OneOperator2_<long, string *, string *>(fileEndsWith));
  Global.Add("makeFolder", "(", new OneOperator1_<long, string *>(makeFolder));
  Global.Add("lockFolder", "(", new OneOperator1_<long, string *>(lockFolder));
  Global.Add("writeProbe", "(", new OneOperator1_<long, string *>(writeProbe));
  Global.Add("cleanOutputs", "(", new OneOperator1_<long, string *>(cleanOutputs));
  Global.Add("listError", "(", new OneOperator0<long>(listError));
  Global.Add("outputObstacle", "(",
             new OneOperator3s_<string *, string *, string *, string *>(outputObstacle));
  Global.Add("claimOutput", "(", new OneOperator1_<long, string *>(claimOutput));
  Global.Add("writeTextFile", "(", new OneOperator2_<long, string *, string *>(writeTextFile));
  Global.Add("appendTextFile", "(", new OneOperator2_<long, string *, string *>(appendTextFile));
  Global.Add("replaceTextFile", "(", new OneOperator2_<long, string *, string *>(replaceTextFile));
  Global.Add("completeLines", "(", new OneOperator1_<long, string *>(completeLines));
  Global.Add("runProgram", "(", new OneOperator3_<long, string *, string *, string *>(runProgram));
  Global.Add("inputProblem", "(", new OneOperator1s_<string *, string *>(inputProblem));
  Global.Add("privateTextFile", "(", new OneOperator1s_<string *, string *>(privateTextFile));
  Global.Add("errorText", "(", new OneOperator1s_<string *, long>(errorText));
  Global.Add("realText", "(", new OneOperator1s_<string *, double>(realText));
  Global.Add("pathProblem", "(", new OneOperator1s_<string *, string *>(pathProblem));
  Global.Add("jsonText", "(", new OneOperator1s_<string *, string *>(jsonText));
}

}  // namespace

LOADFUNC(init)
