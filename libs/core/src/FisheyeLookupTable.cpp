#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/ConfigSectionWriter.h>
#include <mrpt_vslam/core/FisheyeLookupTable.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {
namespace {

// Largest distance [px] between neighbouring samples for the automatic steps.
constexpr double kAutoSpacingPx = 0.5;
constexpr float kFloatInf = std::numeric_limits<float>::infinity();

/// Bounds of the samples that hit one pixel while the table is built.
struct TBounds {
    float phi_offset_min = kFloatInf;  ///< [rad] relative to the pixel-centre azimuth
    float phi_offset_max = -kFloatInf;
    float theta_min = kFloatInf;
    float theta_max = -kFloatInf;
};

double checkedStep(double step, double range, const char* key)
{
    if (!(step >= 0) || step > range) {
        throw std::invalid_argument(std::string("FisheyeLookupTable: ") + key + " = " +
                                    std::to_string(mrpt::RAD2DEG(step)) + " deg must be in [0, " +
                                    std::to_string(mrpt::RAD2DEG(range)) + "] (0 = automatic)");
    }
    return step;
}

}  // namespace

void FisheyeLookupTable::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                      const std::string& section)
{
    lut_delta_phi =
        mrpt::DEG2RAD(cfg.read_double(section, "lut_delta_phi_deg", mrpt::RAD2DEG(lut_delta_phi)));
    lut_delta_theta = mrpt::DEG2RAD(
        cfg.read_double(section, "lut_delta_theta_deg", mrpt::RAD2DEG(lut_delta_theta)));
    checkedStep(lut_delta_phi, 2 * M_PI, "lut_delta_phi_deg");
    checkedStep(lut_delta_theta, M_PI, "lut_delta_theta_deg");
}

void FisheyeLookupTable::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                    const std::string& section) const
{
    const ConfigSectionWriter put(cfg, section);
    put("lut_delta_phi_deg", mrpt::RAD2DEG(lut_delta_phi),
        "[deg] azimuth step of the fisheye look-up table (0 = automatic, <= 0.5 px)");
    put("lut_delta_theta_deg", mrpt::RAD2DEG(lut_delta_theta),
        "[deg] off-axis angle step of the look-up table (0 = automatic, <= 0.5 px)");
}

FisheyeLookupTable::FisheyeLookupTable(const PajdlaBaksteinCamera& camera, const TOptions& options)
    : m_camera(camera)
{
    m_camera.validate();
    double delta_phi = checkedStep(options.lut_delta_phi, 2 * M_PI, "lut_delta_phi_deg");
    double delta_theta =
        checkedStep(options.lut_delta_theta, m_camera.max_theta, "lut_delta_theta_deg");

    // Automatic steps: a step δ moves a sample by at most max(1, β)·(dr/dθ)·δθ radially and
    // max(1, β)·r·δφ along the circle (Eq. 1), so bound both by kAutoSpacingPx.
    const double stretch = std::max(1.0, m_camera.beta);
    if (delta_phi == 0) {
        delta_phi = kAutoSpacingPx / (stretch * m_camera.radius(m_camera.max_theta));
    }
    if (delta_theta == 0) {
        constexpr int kProbes = 1000;
        double max_slope = 0;
        for (int i = 0; i <= kProbes; i++) {
            max_slope =
                std::max(max_slope, m_camera.radiusDerivative(m_camera.max_theta * i / kProbes));
        }
        delta_theta = kAutoSpacingPx / (stretch * max_slope);
    }
    const double n_phi = std::ceil(2 * M_PI / delta_phi);
    const double n_theta = std::ceil(m_camera.max_theta / delta_theta);
    if (!(n_phi * (n_theta + 1) <= kMaxSamples))
        throw std::invalid_argument(
            "FisheyeLookupTable: the camera model puts max_theta_deg " +
            std::to_string(std::lround(m_camera.radius(m_camera.max_theta))) +
            " px from the image centre and would take " +
            mrpt::format("%.1e", n_phi * (n_theta + 1)) +
            " samples (at most 5e8): check a, c, beta and max_theta_deg against the image size, "
            "and the look-up table's steps");
    // Shrink the steps so they divide the sampled intervals evenly.
    m_delta_phi = 2 * M_PI / n_phi;
    m_delta_theta = m_camera.max_theta / n_theta;
    build();
}

FisheyeLookupTable::FisheyeLookupTable(const PajdlaBaksteinCamera& camera)
    : FisheyeLookupTable(camera, TOptions())
{
}

void FisheyeLookupTable::build()
{
    const int width = m_camera.width, height = m_camera.height;
    const double u0 = m_camera.u0, v0 = m_camera.v0, beta = m_camera.beta;

    // Azimuth of each pixel centre seen from the image centre: the reference φ ranges are
    // unwrapped against.
    std::vector<float> phi_ref(static_cast<size_t>(width) * height);
    for (int row = 0; row < height; row++) {
        for (int col = 0; col < width; col++) {
            phi_ref[static_cast<size_t>(row) * width + col] =
                static_cast<float>(std::atan2(row / beta - v0, col - u0));
        }
    }

    const int n_phi = static_cast<int>(std::lround(2 * M_PI / m_delta_phi));
    const int n_theta = static_cast<int>(std::lround(m_camera.max_theta / m_delta_theta));
    std::vector<double> phis(n_phi), cos_phi(n_phi), sin_phi(n_phi);
    for (int l = 0; l < n_phi; l++) {
        phis[l] = -M_PI + l * m_delta_phi;
        cos_phi[l] = std::cos(phis[l]);
        sin_phi[l] = std::sin(phis[l]);
    }

    // Step 1 (Gamallo et al. 2013, Sec. III-A): sample (φ, θ) and project with Eq. 1.
    std::vector<TBounds> bounds(phi_ref.size());
    for (int k = 0; k <= n_theta; k++) {
        const double theta = k * m_delta_theta;
        const double r = m_camera.radius(theta);
        const auto theta_f = static_cast<float>(theta);
        for (int l = 0; l < n_phi; l++) {
            const double u = u0 + r * cos_phi[l];
            const double v = beta * (v0 + r * sin_phi[l]);
            const double col = std::floor(u + 0.5), row = std::floor(v + 0.5);
            if (!(col >= 0 && row >= 0 && col < width && row < height)) continue;
            const size_t idx = static_cast<size_t>(row) * width + static_cast<size_t>(col);
            // Step 2: keep the min and max of φ and θ per pixel (φ unwrapped around phi_ref).
            const auto offset = static_cast<float>(mrpt::math::wrapToPi(phis[l] - phi_ref[idx]));
            TBounds& b = bounds[idx];
            b.phi_offset_min = std::min(b.phi_offset_min, offset);
            b.phi_offset_max = std::max(b.phi_offset_max, offset);
            b.theta_min = std::min(b.theta_min, theta_f);
            b.theta_max = std::max(b.theta_max, theta_f);
        }
    }

    // Store ranges as centre and half-width.
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    m_cells.assign(bounds.size(), TCell{kNaN, kNaN, kNaN, kNaN});
    m_valid_pixels = 0;
    for (size_t idx = 0; idx < bounds.size(); idx++) {
        const TBounds& b = bounds[idx];
        if (b.theta_min > b.theta_max) continue;
        const double mid_offset = 0.5 * (double(b.phi_offset_min) + b.phi_offset_max);
        m_cells[idx] =
            TCell{static_cast<float>(mrpt::math::wrapToPi(phi_ref[idx] + mid_offset)),
                  0.5f * (b.phi_offset_max - b.phi_offset_min), 0.5f * (b.theta_min + b.theta_max),
                  0.5f * (b.theta_max - b.theta_min)};
        m_valid_pixels++;
    }
}

const FisheyeLookupTable::TCell& FisheyeLookupTable::cell(int col, int row) const
{
    if (col < 0 || row < 0 || col >= m_camera.width || row >= m_camera.height) {
        throw std::out_of_range("FisheyeLookupTable::cell: pixel (" + std::to_string(col) + ", " +
                                std::to_string(row) + ") is outside the " +
                                std::to_string(m_camera.width) + "x" +
                                std::to_string(m_camera.height) + " image");
    }
    return m_cells[static_cast<size_t>(row) * m_camera.width + col];
}

FisheyeLookupTable::TLookup FisheyeLookupTable::lookup(double u, double v) const
{
    TLookup out;
    // Nearest pixel: the one whose square [c − ½, c + ½) contains the point.
    const double col = std::floor(u + 0.5), row = std::floor(v + 0.5);
    if (!(col >= 0 && row >= 0 && col < m_camera.width && row < m_camera.height)) return out;
    const TCell& c = cell(static_cast<int>(col), static_cast<int>(row));
    if (std::isnan(c.phi)) return out;
    out.valid = true;
    out.phi = c.phi;
    out.theta = c.theta;
    out.phi_half_range = c.phi_half_range;
    out.theta_half_range = c.theta_half_range;
    return out;
}

}  // namespace mrpt_vslam::core
