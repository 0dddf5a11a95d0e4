#pragma once

#include <mrpt_vslam/core/USurfDescriptor.h>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

namespace mrpt_vslam::multirobot {

/** A landmark that may explain a measurement: its id and descriptor distance E (Eq. 16). */
struct TLandmarkCandidate {
    uint32_t id = 0;
    float E = 0;  ///< (d_t − d_j)(d_t − d_j)^T, squared Euclidean distance of the descriptors
};

/** The descriptors d_j of all landmarks ever created, under their ids, shared by every
 *  particle's map, plus a spatial hash of the position each landmark was created at.
 *
 *  Why: Alg. 1 lines 19-32 pick, among the landmarks with Mahalanobis distance D ≤ D0, the one
 *  with the smallest descriptor distance E, and create a landmark if that E exceeds E0. That
 *  is the landmark of smallest E among those with D ≤ D0 and E ≤ E0, so the E test can run
 *  first. E does not depend on the particle, so one search per measurement (here) serves all
 *  M particles, which then evaluate D only for the few candidates they hold.
 *
 *  The search also bounds the distance between a candidate's creation position and the
 *  measured point (a spatial index instead of a scan of all landmarks); the caller chooses a
 *  radius that covers the spread of the particles and the Mahalanobis gate.
 *
 *  With known correspondences (CVisualLandmarksMap's associate_by_identity) the pool also
 *  records which landmark id each identity started, so that all particles use that one. */
class LandmarkDescriptorPool {
  public:
    using TDescriptor = core::USurfDescriptor::TDescriptor;

    /// \param cell_size edge of the spatial hash cells [m]
    explicit LandmarkDescriptorPool(double cell_size = 1.0);

    /// A new id for a landmark with this descriptor, created at `position` (map frame).
    uint32_t add(const TDescriptor& descriptor, const Eigen::Vector3d& position);
    /// Stores a landmark under a given id (reading a saved map); the id must be unused.
    void addWithId(uint32_t id, const TDescriptor& descriptor, const Eigen::Vector3d& position);

    /// Ids handed out so far (also one more than the largest id).
    size_t size() const { return m_descriptors.size(); }
    bool contains(uint32_t id) const { return id < m_used.size() && m_used[id]; }
    const TDescriptor& descriptor(uint32_t id) const { return m_descriptors[id]; }
    const Eigen::Vector3d& creationPosition(uint32_t id) const { return m_positions[id]; }

    /** Appends to `out` every landmark created within `radius` of `center` whose descriptor
     *  distance to `query` is E ≤ max_E, in increasing E (ties: increasing id), the order in
     *  which Alg. 1 line 29 prefers them. */
    void findCandidates(const Eigen::Vector3d& center, double radius, const TDescriptor& query,
                        double max_E, std::vector<TLandmarkCandidate>& out) const;

    /** Takes the landmarks that no map holds any more out of findCandidates(): every id whose
     *  bit is clear in `held` (a bit set of ids as LandmarkStore::addIdsTo() makes), except the
     *  landmarks of identities. Valid where a landmark no map holds never comes back (the
     *  particle filter: its particles only create landmarks with new ids). Returns how many
     *  landmarks the search still holds. */
    size_t forgetAllBut(const std::vector<uint32_t>& held);

    /// The landmark the first reading of this identity started (known correspondences), if any.
    std::optional<uint32_t> landmarkOfIdentity(int64_t identity) const;
    /// Records that landmark `id` stands for `identity` (the first one recorded stays).
    void setLandmarkOfIdentity(int64_t identity, uint32_t id)
    {
        m_identities.emplace(identity, id);
    }
    /// Every (identity, landmark id) recorded, by increasing identity.
    std::vector<std::pair<int64_t, uint32_t>> identities() const;

    /// (d_a − d_b)(d_a − d_b)^T (Eq. 16).
    static float squaredDistance(const TDescriptor& a, const TDescriptor& b);

    double cellSize() const { return m_cell; }

  private:
    int64_t cellKey(int64_t ix, int64_t iy, int64_t iz) const;
    int64_t cellIndex(double v) const;
    void index(uint32_t id);

    double m_cell;
    std::vector<TDescriptor> m_descriptors;
    std::vector<Eigen::Vector3d> m_positions;
    std::vector<bool> m_used;
    std::unordered_map<int64_t, std::vector<uint32_t>> m_grid;
    std::unordered_map<int64_t, uint32_t> m_identities;
};

}  // namespace mrpt_vslam::multirobot
