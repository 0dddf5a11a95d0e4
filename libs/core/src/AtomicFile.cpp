#include <mrpt_vslam/core/AtomicFile.h>

#include <cstdio>
#include <stdexcept>

namespace mrpt_vslam::core {

AtomicFile::AtomicFile(const std::string& file) : m_file(file), m_tmp(file + ".tmp"), m_out(m_tmp)
{
    if (!m_out) throw std::runtime_error(file + ": cannot create file for writing");
}

AtomicFile::~AtomicFile()
{
    if (!m_committed) {
        m_out.close();
        std::remove(m_tmp.c_str());
    }
}

void AtomicFile::commit()
{
    m_out.flush();
    if (!m_out) throw std::runtime_error(m_file + ": write failed");
    m_out.close();
    commitRename(m_tmp, m_file);
    m_committed = true;
}

void AtomicFile::commitRename(const std::string& tmp_file, const std::string& file)
{
    if (std::rename(tmp_file.c_str(), file.c_str()) != 0)
        throw std::runtime_error(file + ": cannot rename " + tmp_file + " into place");
}

}  // namespace mrpt_vslam::core
