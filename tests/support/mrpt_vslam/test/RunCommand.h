#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace mrpt_vslam::test {

/// Exit code and output of a shell command.
struct TCommandResult {
    int exit_code = -1;  ///< -1 if the command did not exit normally
    std::string out;     ///< stdout and stderr
};

/// Runs `command` in a shell, its stdout + stderr going to `log`, and returns both.
inline TCommandResult runCommand(const std::string& command, const std::filesystem::path& log)
{
    const int status = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

/// Lines of a command's output (its newline characters).
inline int lineCount(const std::string& text)
{
    int n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

}  // namespace mrpt_vslam::test
