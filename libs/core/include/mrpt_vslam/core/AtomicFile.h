#pragma once

#include <fstream>
#include <string>

namespace mrpt_vslam::core {

/** A text output file that appears under its name only when complete: writes go to `NAME.tmp`,
 *  commit() flushes, checks and renames it; destruction without commit() removes the temporary,
 *  so an interrupted or failed run never leaves a partial file that looks whole. */
class AtomicFile {
  public:
    explicit AtomicFile(const std::string& file);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return m_out; }
    /// Flushes and renames to the final name; throws std::runtime_error naming the file on failure.
    void commit();

    /// Renames an already written temporary `tmp_file` to `file` (for files written by MRPT).
    static void commitRename(const std::string& tmp_file, const std::string& file);

  private:
    std::string m_file, m_tmp;
    std::ofstream m_out;
    bool m_committed = false;
};

}  // namespace mrpt_vslam::core
