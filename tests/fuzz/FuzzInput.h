#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace mrpt_vslam::fuzz {

/** Values drawn from a fuzzer's bytes, front to back; past the end every draw is 0. Numbers are
 *  chosen by a selector byte among the values that break code (0, ±1, NaN, ±inf, huge, tiny,
 *  negative) or read raw from the next 8 bytes. */
class FuzzInput {
  public:
    FuzzInput(const uint8_t* data, size_t size) : m_data(data), m_size(size) {}

    uint8_t byte() { return m_pos < m_size ? m_data[m_pos++] : 0; }

    /// Two bytes, high first (drawn in this order: the operands of | are unsequenced).
    unsigned word()
    {
        const unsigned high = byte();
        return high << 8 | byte();
    }

    /// An integer in [0, n) (n > 0).
    size_t index(size_t n) { return word() % n; }

    double number()
    {
        switch (byte() % 12) {
            case 0:
                return 0;
            case 1:
                return 1;
            case 2:
                return -1;
            case 3:
                return std::numeric_limits<double>::quiet_NaN();
            case 4:
                return std::numeric_limits<double>::infinity();
            case 5:
                return -std::numeric_limits<double>::infinity();
            case 6:
                return 1e300;
            case 7:
                return -1e300;
            case 8:
                return 1e-300;
            case 9:
                return (static_cast<double>(byte()) - 128) / 16;  // ±8 in steps of 1/16
            case 10:
                return (static_cast<double>(byte()) - 128) * 100;
            default: {
                uint64_t bits = 0;
                for (int i = 0; i < 8; i++) bits = bits << 8 | byte();
                double v;
                std::memcpy(&v, &bits, sizeof v);
                return v;
            }
        }
    }

    /// A finite number in [low, high] (the odometry, which the readers have already checked).
    double finite(double low, double high)
    {
        return low + (high - low) * (static_cast<double>(word()) / 65535.0);
    }

    /// The bytes not drawn yet, as text.
    std::string rest()
    {
        std::string s(reinterpret_cast<const char*>(m_data) + m_pos, m_size - m_pos);
        m_pos = m_size;
        return s;
    }

  private:
    const uint8_t* m_data;
    size_t m_size, m_pos = 0;
};

/** A file in a folder of this process's own, written with the given bytes; the folder is
 *  removed at exit. \param name the file's name (e.g. "input.rawlog") */
std::string writeScratchFile(const std::string& name, const uint8_t* data, size_t size);
/// The process's own folder (created on first use).
std::string scratchFolder();

}  // namespace mrpt_vslam::fuzz
