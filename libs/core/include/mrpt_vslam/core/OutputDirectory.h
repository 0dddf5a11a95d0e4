#pragma once

#include <string>

namespace mrpt_vslam::core {

/** The output folder of a run (`--out`): created with its parents when constructed, then the
 *  place every output file path comes from.
 *
 *  Usage: `OutputDirectory out(args.outDir); report.write(out.file("run.json"));`
 */
class OutputDirectory {
  public:
    /** Creates `dir` and any missing parents. Throws std::runtime_error
     *  `"<dir>: cannot create output folder: <reason>"` if it cannot, or if `dir` exists and is
     *  not a folder. */
    explicit OutputDirectory(const std::string& dir);

    const std::string& path() const { return m_dir; }
    /** `<dir>/<name>`. */
    std::string file(const std::string& name) const;

  private:
    std::string m_dir;
};

}  // namespace mrpt_vslam::core
