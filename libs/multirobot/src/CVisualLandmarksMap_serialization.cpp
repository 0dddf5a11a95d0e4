#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>

namespace mrpt_vslam::multirobot {

uint8_t CVisualLandmarksMap::serializeGetVersion() const { return 4; }

void CVisualLandmarksMap::serializeTo(mrpt::serialization::CArchive& out) const
{
    out << genericMapParams;
    // Options travel with the map: CMultiMetricMap copies (particle resampling) serialize it.
    const auto& io = insertionOptions;
    out << io.D0 << io.E0 << io.p0 << io.search_radius << io.grid_cell_size << io.joint_association
        << io.associate_by_identity;
    out << renderOptions.draw_ellipsoids << renderOptions.ellipsoid_quantiles
        << renderOptions.point_size;
    out << static_cast<uint32_t>(m_store.size());
    m_store.forEach([&](uint32_t id, const TVisualLandmark& lm) {
        out << id;
        for (int i = 0; i < 3; i++) out << lm.mean[i];
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++) out << lm.cov(r, c);
        out << lm.times_seen << lm.seen_by;
        for (const float v : m_pool->descriptor(id)) out << v;
        for (int i = 0; i < 3; i++) out << m_pool->creationPosition(id)[i];
    });
    const auto identities = m_pool->identities();
    out << static_cast<uint32_t>(identities.size());
    for (const auto& [identity, id] : identities) out << identity << id;
}

void CVisualLandmarksMap::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version)
{
    if (version > 4) MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    in >> genericMapParams;
    auto& io = insertionOptions;
    in >> io.D0 >> io.E0 >> io.p0 >> io.search_radius >> io.grid_cell_size;
    io.joint_association = false;
    if (version >= 2) in >> io.joint_association;  // version 2
    io.associate_by_identity = false;
    if (version >= 3) in >> io.associate_by_identity;  // version 3
    in >> renderOptions.draw_ellipsoids >> renderOptions.ellipsoid_quantiles >>
        renderOptions.point_size;
    if (!(io.grid_cell_size > 0)) THROW_EXCEPTION("CVisualLandmarksMap: invalid grid cell size");
    m_store.clear();
    m_pool = std::make_shared<LandmarkDescriptorPool>(io.grid_cell_size);
    uint32_t n;
    in >> n;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t id;
        TVisualLandmark lm;
        LandmarkDescriptorPool::TDescriptor d;
        Eigen::Vector3d created;
        in >> id;
        for (int i = 0; i < 3; i++) in >> lm.mean[i];
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++) {
                in >> lm.cov(r, c);
                lm.cov(c, r) = lm.cov(r, c);
            }
        in >> lm.times_seen >> lm.seen_by;
        if (version >= 1 && version <= 3) {  // versions 1-3: evaluation fields, dropped
            int64_t identity;
            uint32_t identity_conflicts;
            in >> identity >> identity_conflicts;
        }
        for (float& v : d) in >> v;
        for (int i = 0; i < 3; i++) in >> created[i];
        m_pool->addWithId(id, d, created);
        m_store.insert(id, lm);
    }
    if (version >= 3) {
        in >> n;
        for (uint32_t k = 0; k < n; k++) {
            int64_t identity;
            uint32_t id;
            in >> identity >> id;
            m_pool->setLandmarkOfIdentity(identity, id);
        }
    }
}

}  // namespace mrpt_vslam::multirobot
