// headless: FreeFem++ without a display, loaded from freefem++.pref (before the script is compiled).
// The graphical FreeFem++ opens a pipe to ffglut when it starts, even for a script that never plots.
// Without a display ffglut exits at once, and FreeFem++'s last write to the dead pipe (its plot
// header, flushed at exit) kills it with SIGPIPE: exit 141 and the buffered output lost, whenever the
// output goes to a file or a pipe. With neither DISPLAY nor WAYLAND_DISPLAY set, this plugin closes
// that pipe at load time and leaves FreeFem++ as -nw would. With a display it does nothing.
// Provides nothing to scripts.
#include "ff++.hpp"
#include <csignal>
#include <cstdio>
#include <cstdlib>

extern FILE *ThePlotStream;
extern bool NoGraphicWindow;

namespace {

bool hasDisplay() {
  const char *x11 = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

void init() {
  if (hasDisplay() || !ThePlotStream) return;
  void (*previous)(int) = signal(SIGPIPE, SIG_IGN);   // ffglut may have exited already
  pclose(ThePlotStream);
  signal(SIGPIPE, previous);
  ThePlotStream = 0;
  NoGraphicWindow = true;
}

}  // namespace

LOADFUNC(init)
