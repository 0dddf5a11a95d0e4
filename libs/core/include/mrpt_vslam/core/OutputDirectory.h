#pragma once

#include <cstddef>
#include <string>

namespace mrpt_vslam::core {

/** The output folder of a run (`--out`): created with its parents when constructed, then the
 *  place every output file path comes from.
 *
 *  Usage: `OutputDirectory out(args.outDir); out.removeEarlierRun();
 *  report.write(out.file("run.json"));`
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

    /** Whether `file` is in this folder under a name isRunFile() gives: a file a run writes
     *  over (an input there, such as `DIR/config.ini` given as the config, would be lost). */
    bool holdsRunFile(const std::string& file) const;

    /** Removes the files of an earlier run from the folder (those isRunFile() names), so that
     *  none of them stands beside this run's as if it were one of them (a second robot's path
     *  after a one-robot run, say); every other file stays. Returns how many it removed. Throws
     *  std::runtime_error `"<file>: cannot remove: <reason>"`. */
    size_t removeEarlierRun() const;

    /** Whether `name` is one of the files the SLAM apps and vslam-eval write into a run folder
     *  (doc/data-formats.md, "Run outputs"): run.json, metrics.json, config.ini, final.3Dscene,
     *  final_map.gz, steps.txt, observations.txt, paths.png, errors.png, landmark_errors.png,
     *  STEM.tum and STEM_<X>.tum for STEM estimated_path, odometry_path or filter_path, and
     *  STEM.txt and STEM_<X>.txt for STEM map, particle_map or filter_map. */
    static bool isRunFile(const std::string& name);

  private:
    std::string m_dir;
};

}  // namespace mrpt_vslam::core
