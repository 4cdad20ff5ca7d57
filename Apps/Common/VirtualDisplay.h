// For the programs that render (header-only): VTK renders through X11/GLX
// only, so without a display a program runs itself again inside a virtual X
// server (xvfb-run), offscreen.
#ifndef VirtualDisplay_h
#define VirtualDisplay_h

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

namespace thintissue::apps
{

/// Runs the program again as `xvfb-run -a ... <argv> --offscreen`; returns
/// only on failure (no xvfb-run, or already re-run once: no loop).
inline void reexecuteUnderVirtualDisplay(int argc, char* argv[])
{
  if (std::getenv("THINTISSUE_UNDER_XVFB") != nullptr)
  {
    return;
  }
  setenv("THINTISSUE_UNDER_XVFB", "1", 1);
  std::vector<std::string> words = { "xvfb-run", "-a", "-s", "-screen 0 1280x1024x24" };
  for (int i = 0; i < argc; ++i)
  {
    words.emplace_back(argv[i]);
  }
  words.emplace_back("--offscreen");
  std::vector<char*> arguments;
  for (std::string& w : words)
  {
    arguments.push_back(w.data());
  }
  arguments.push_back(nullptr);
  execvp(arguments[0], arguments.data());
}

/// True when there is an X display. Otherwise the program runs again under
/// xvfb-run (this call does not return then); if it cannot, says so as
/// `program` and returns false.
inline bool haveDisplayOrRerun(int argc, char* argv[], const char* program)
{
  const char* display = std::getenv("DISPLAY");
  if (display != nullptr && display[0] != '\0')
  {
    return true;
  }
  reexecuteUnderVirtualDisplay(argc, argv);
  std::cerr << program
            << ": no X display and no working xvfb-run; install xvfb or run with DISPLAY set\n";
  return false;
}

} // namespace thintissue::apps

#endif
