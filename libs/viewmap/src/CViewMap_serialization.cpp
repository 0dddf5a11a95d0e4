#include <mrpt/core/format.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/viewmap/CViewMap.h>

#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::viewmap {

namespace {

/// Upper bounds on what one view may hold: a corrupt count fails here, not in an allocation.
constexpr uint32_t kMaxFeaturesPerView = 1000000;
constexpr uint32_t kMaxImageFileLength = 4096;

/// Reads a finite value, else throws naming it.
template <typename T>
T readFinite(mrpt::serialization::CArchive& in, const std::string& what)
{
    T v;
    in >> v;
    if (!std::isfinite(v)) throw std::runtime_error(what + " is not finite");
    return v;
}

/// Reads exactly n bytes (CArchive::ReadBuffer accepts a short read).
void readExact(mrpt::serialization::CArchive& in, void* buffer, size_t n, const std::string& what)
{
    if (n && in.ReadBuffer(buffer, n) != n) throw std::runtime_error(what + ": truncated");
}

void writeFeatures(mrpt::serialization::CArchive& out, const TViewFeatures& f)
{
    out << static_cast<uint32_t>(f.size());
    for (size_t k = 0; k < f.size(); k++) {
        const auto c = static_cast<Eigen::Index>(k);
        out << f.pixels(0, c) << f.pixels(1, c) << f.scales[k] << f.laplacian_signs[k];
        out << f.rays(0, c) << f.rays(1, c) << f.rays(2, c);
        for (const float d : f.descriptors[k]) out << d;
    }
}

TViewFeatures readFeatures(mrpt::serialization::CArchive& in, const std::string& what)
{
    uint32_t n = 0;
    in >> n;
    if (n > kMaxFeaturesPerView)
        throw std::runtime_error(mrpt::format("%s: %u feature points (corrupt file? at most %u)",
                                              what.c_str(), n, kMaxFeaturesPerView));
    // Grown point by point, so a count larger than the data fails at the end of the stream.
    std::vector<float> pixels;
    std::vector<double> rays;
    TViewFeatures f;
    for (uint32_t k = 0; k < n; k++) {
        const std::string p = what + mrpt::format(", point %u", k);
        pixels.push_back(readFinite<float>(in, p + " pixel u"));
        pixels.push_back(readFinite<float>(in, p + " pixel v"));
        f.scales.push_back(readFinite<float>(in, p + " scale"));
        int8_t sign = 0;
        in >> sign;
        f.laplacian_signs.push_back(sign);
        for (int i = 0; i < 3; i++) rays.push_back(readFinite<double>(in, p + " ray"));
        core::USurfDescriptor::TDescriptor d;
        for (float& v : d) v = readFinite<float>(in, p + " descriptor");
        f.descriptors.push_back(d);
    }
    f.pixels = Eigen::Map<const Eigen::Matrix2Xf>(pixels.data(), 2, n);
    f.rays = Eigen::Map<const Eigen::Matrix3Xd>(rays.data(), 3, n);
    return f;
}

}  // namespace

uint8_t CViewMap::serializeGetVersion() const { return 0; }

void CViewMap::serializeTo(mrpt::serialization::CArchive& out) const
{
    out << genericMapParams;
    // Options travel with the map: CMultiMetricMap copies serialize it.
    out << renderOptions.draw_ellipses << renderOptions.ellipse_quantiles << renderOptions.view_size
        << renderOptions.draw_ids;
    out << static_cast<uint32_t>(m_views.size());
    for (const TView& v : m_views) {
        out << v.id << v.pose.x << v.pose.y << v.pose.phi;
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++) out << v.covariance(r, c);
        out << v.timestamp;
        out << static_cast<uint32_t>(v.image_file.size());
        out.WriteBuffer(v.image_file.data(), v.image_file.size());
        writeFeatures(out, v.features);
    }
}

void CViewMap::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version)
{
    if (version != 0) MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    in >> genericMapParams;
    TRenderOptions render;
    in >> render.draw_ellipses >> render.ellipse_quantiles >> render.view_size >> render.draw_ids;
    if (!(render.ellipse_quantiles > 0 && std::isfinite(render.ellipse_quantiles) &&
          render.view_size > 0 && std::isfinite(render.view_size)))
        throw std::runtime_error("CViewMap: invalid render options (corrupt file?)");
    uint32_t n = 0;
    in >> n;
    std::vector<TView> views;  // grown view by view, as the features
    for (uint32_t k = 0; k < n; k++) {
        const std::string what = mrpt::format("CViewMap: view %u", k);
        TView v;
        in >> v.id;
        if (v.id != k)
            throw std::runtime_error(what + mrpt::format(" has id %u (corrupt file?)", v.id));
        in >> v.pose.x >> v.pose.y >> v.pose.phi;
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++) {
                in >> v.covariance(r, c);
                v.covariance(c, r) = v.covariance(r, c);
            }
        v.timestamp = readFinite<double>(in, what + " timestamp");
        uint32_t length = 0;
        in >> length;
        if (length > kMaxImageFileLength)
            throw std::runtime_error(what + mrpt::format(": image file name of %u bytes "
                                                         "(corrupt file?)",
                                                         length));
        v.image_file.resize(length);
        readExact(in, v.image_file.data(), length, what + " image file");
        v.features = readFeatures(in, what);
        checkView(v, what);
        views.push_back(std::move(v));
    }
    renderOptions = render;
    m_views = std::move(views);
}

}  // namespace mrpt_vslam::viewmap
