// files: a run's dealings with the file system and with other programs, without a shell (built by
// `make` with ff-c++; loaded by include/core/output.idp). A path goes to the system calls as it is:
// nothing a user types is spliced into a command line, so a quote, a blank or a leading '-' in a
// path is only a character of a name.
//
//   pathKind(path): 0 nothing there, 1 a regular file, 2 a directory, 3 a symbolic link, 4 else
//     (lstat: a link is not followed).
//   fileBytes(path): its size in bytes (a link followed), -1 when it cannot be read.
//   fileEndsWith(path, text): 1 when the file's last bytes are text (trailing white space ignored): how
//     a file written by a writer that reports no error (FreeFEM's savevtk) is known to be whole.
//   makeFolder(path): creates the folder and its missing parents (mkdir -p); 0, or the errno.
//   writeProbe(folder): creates and removes a file in it; 0, or the errno.
//   lockFolder(folder): an exclusive lock on folder/.lock (flock), held until the process ends: 0,
//     1 when another process holds it, or the errno.
//   removeOutput(path): removes a regular file or a symbolic link (never what a link points to, never a
//     folder); 0 when nothing is left there, or the errno (EISDIR for a folder).
//   removeListedOutputs(folder): removes the files that folder/.outputs lists (one name a line: plain
//     names only, no '/', not "." or ".."; regular files and links only), then .outputs itself;
//     returns how many it removed, or -1 when .outputs cannot be read. No limit on their number.
//   renameFile(from, to): rename(2) (atomic within a file system); 0, or the errno.
//   completeLines(path): the number of lines of a text file that ends with a newline (every file the
//     suite writes does); -1 when the file cannot be read, -2 when its last line has no newline. A
//     write cut short (a full disk: the stream's buffered tail lost) leaves fewer lines or no final
//     newline: how the scripts check their writes, FreeFEM's ofstream reporting no error.
//   runProgram(program, arguments, log): runs program with its arguments (one per line of
//     `arguments`) by fork and execvp, no shell, standard output and error into the file `log`;
//     returns its exit status, 127 when it could not be started, 128 + n when signal n ended it.
//   writeTextFile(path, text), appendTextFile(path, text): text into the file (replacing it, or at its
//     end), every step checked (open, write, close; fsync for a whole file): 0, or the errno (ENOSPC
//     on a full disk). FreeFEM's ofstream reports no error: a write it loses is silent.
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
// change the file system (makeFolder, writeProbe, lockFolder, removeOutput, removeListedOutputs,
// renameFile, runProgram, writeTextFile, appendTextFile) does nothing and returns success.
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern long mpirank;   // FreeFEM's: 0 under FreeFem++

namespace {

bool writesHere() { return mpirank == 0; }

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
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == ' ' || tail.back() == '\r')) tail.pop_back();
  return tail.size() >= text->size() && tail.compare(tail.size() - text->size(), text->size(), *text) == 0;
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

long writeProbe(string *const &folder) {
  if (!writesHere()) return 0;
  std::string probe = *folder + "/.write_probe";
  int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
  if (fd < 0) return errno;
  close(fd);
  unlink(probe.c_str());
  return 0;
}

int heldLock = -1;   // kept open for the process's life: the lock goes with it
long lockFolder(string *const &folder) {
  if (!writesHere()) return 0;
  std::string file = *folder + "/.lock";
  int fd = open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW, 0644);
  if (fd < 0) return errno;
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    int error = errno;
    close(fd);
    return error == EWOULDBLOCK ? 1 : error;
  }
  if (heldLock >= 0) close(heldLock);
  heldLock = fd;
  return 0;
}

long removeAt(const std::string &path) {
  if (!writesHere()) return 0;
  struct stat info;
  if (lstat(path.c_str(), &info) != 0) return errno == ENOENT ? 0 : errno;
  if (S_ISDIR(info.st_mode)) return EISDIR;
  if (!S_ISREG(info.st_mode) && !S_ISLNK(info.st_mode)) return EPERM;
  return unlink(path.c_str()) == 0 ? 0 : errno;
}

long removeOutput(string *const &path) { return removeAt(*path); }

long removeListedOutputs(string *const &folder) {
  if (!writesHere()) return 0;
  std::string list = *folder + "/.outputs";
  FILE *f = fopen(list.c_str(), "r");
  if (!f) return errno == ENOENT ? 0 : -1;
  long removed = 0;
  std::vector<char> line(4096);
  while (fgets(line.data(), int(line.size()), f)) {
    std::string name(line.data());
    while (!name.empty() && (name.back() == '\n' || name.back() == '\r')) name.pop_back();
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos) continue;
    struct stat info;
    std::string path = *folder + "/" + name;
    if (lstat(path.c_str(), &info) != 0) continue;
    if ((S_ISREG(info.st_mode) || S_ISLNK(info.st_mode)) && unlink(path.c_str()) == 0) removed++;
  }
  fclose(f);
  removeAt(list);
  return removed;
}

long renameFile(string *const &from, string *const &to) {
  if (!writesHere()) return 0;
  return rename(from->c_str(), to->c_str()) == 0 ? 0 : errno;
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
  pid_t pid = fork();
  if (pid < 0) return 127;
  if (pid == 0) {
    int fd = open(log->c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
    if (fd < 0) _exit(127);
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) { dup2(devnull, 0); close(devnull); }
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 127;
}

long writeText(const std::string &path, const std::string &text, bool append) {
  if (!writesHere()) return 0;
  int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_NOFOLLOW | (append ? O_APPEND : O_TRUNC), 0644);
  if (fd < 0) return errno;
  size_t done = 0;
  while (done < text.size()) {
    ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      int error = errno;
      close(fd);
      return error;
    }
    done += size_t(n);
  }
  // a whole file is synced (a file system may report a lost write only then); an appended line is not
  // (thousands of syncs for a pressure.csv): its write and close report a full disk (ext4 reserves
  // the blocks of a buffered write at write time, tmpfs allocates them then)
  if (!append && fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {   // (fsync is not meaningful on every file)
    int error = errno;
    close(fd);
    return error;
  }
  return close(fd) == 0 ? 0 : errno;
}
long writeTextFile(string *const &path, string *const &text) { return writeText(*path, *text, false); }
long appendTextFile(string *const &path, string *const &text) { return writeText(*path, *text, true); }

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
  Global.Add("writeProbe", "(", new OneOperator1_<long, string *>(writeProbe));
  Global.Add("lockFolder", "(", new OneOperator1_<long, string *>(lockFolder));
  Global.Add("removeOutput", "(", new OneOperator1_<long, string *>(removeOutput));
  Global.Add("removeListedOutputs", "(", new OneOperator1_<long, string *>(removeListedOutputs));
  Global.Add("renameFile", "(", new OneOperator2_<long, string *, string *>(renameFile));
  Global.Add("completeLines", "(", new OneOperator1_<long, string *>(completeLines));
  Global.Add("runProgram", "(", new OneOperator3_<long, string *, string *, string *>(runProgram));
  Global.Add("writeTextFile", "(", new OneOperator2_<long, string *, string *>(writeTextFile));
  Global.Add("appendTextFile", "(", new OneOperator2_<long, string *, string *>(appendTextFile));
  Global.Add("privateTextFile", "(", new OneOperator1s_<string *, string *>(privateTextFile));
  Global.Add("errorText", "(", new OneOperator1s_<string *, long>(errorText));
  Global.Add("realText", "(", new OneOperator1s_<string *, double>(realText));
  Global.Add("pathProblem", "(", new OneOperator1s_<string *, string *>(pathProblem));
  Global.Add("jsonText", "(", new OneOperator1s_<string *, string *>(jsonText));
}

}  // namespace

LOADFUNC(init)
