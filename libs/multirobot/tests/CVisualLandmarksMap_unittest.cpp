#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <Eigen/Dense>
#include <algorithm>
#include <functional>
#include <limits>
#include <random>
#include <tuple>

using namespace mrpt_vslam::multirobot;

namespace {
LandmarkDescriptorPool::TDescriptor unitDescriptor(int seed)
{
    std::mt19937 gen(seed);
    std::normal_distribution<float> n;
    LandmarkDescriptorPool::TDescriptor d;
    float norm = 0;
    for (auto& v : d) {
        v = n(gen);
        norm += v * v;
    }
    for (auto& v : d) v /= std::sqrt(norm);
    return d;
}

/// A measurement already in the map frame (robot at the origin, identity rotation).
TLandmarkMeasurement measurement(const Eigen::Vector3d& z, double sigma, int descriptor_seed)
{
    TLandmarkMeasurement m;
    m.z = z;
    m.R = Eigen::Matrix3d::Identity() * sigma * sigma;
    m.d = unitDescriptor(descriptor_seed);
    m.depth = z.x();
    return m;
}

TVisualLandmark landmarkAt(const Eigen::Vector3d& p, double sigma)
{
    TVisualLandmark lm;
    lm.mean = p;
    lm.cov = Eigen::Matrix3d::Identity() * sigma * sigma;
    lm.times_seen = 1;
    lm.seen_by = 1;
    return lm;
}

TFusionResult fuseAtOrigin(CVisualLandmarksMap& map, const TLandmarkMeasurement& m,
                           unsigned robot = 0)
{
    const TMapMeasurement in_map = toMapFrame(m, {0, 0, 0});
    auto candidates = map.findCandidates(m, in_map);
    return map.fuse(m, in_map, candidates, robot);
}
}  // namespace

TEST(CVisualLandmarksMap, AmongGatedLandmarksTheDescriptorDecides)
{
    // Alg. 1 lines 27-29: two landmarks 5 cm apart, both inside D0; the one with the closer
    // descriptor wins even though it is farther in Mahalanobis distance.
    CVisualLandmarksMap map;
    const uint32_t a = map.addLandmark(landmarkAt({2, 0, 1}, 0.1), unitDescriptor(1));
    const uint32_t b = map.addLandmark(landmarkAt({2, 0.05, 1}, 0.1), unitDescriptor(2));
    auto m = measurement({2, 0.01, 1}, 0.05, 2);  // nearer to a, descriptor of b
    const auto r = fuseAtOrigin(map, m, 1);
    EXPECT_FALSE(r.created);
    EXPECT_EQ(r.id, b);
    EXPECT_NE(r.id, a);
    EXPECT_EQ(map.landmarks().find(b)->seen_by, 0b11u) << "robots 0 and 1 measured it";
    EXPECT_EQ(map.landmarks().find(b)->times_seen, 2u);
}

TEST(CVisualLandmarksMap, SameDescriptorOutsideTheGateIsANewLandmark)
{
    // repetitive texture: the descriptor matches, the position does not (line 28)
    CVisualLandmarksMap map;
    map.insertionOptions.search_radius = 5;
    map.addLandmark(landmarkAt({2, 0, 1}, 0.05), unitDescriptor(1));
    const auto r = fuseAtOrigin(map, measurement({2, 1.0, 1}, 0.05, 1));
    EXPECT_TRUE(r.created);
    EXPECT_EQ(map.size(), 2u);
    EXPECT_NEAR(r.log_w, std::log(map.insertionOptions.p0), 1e-12) << "line 36: ω = p0";
}

TEST(CVisualLandmarksMap, DifferentDescriptorAtTheSamePlaceIsANewLandmark)
{
    CVisualLandmarksMap map;
    map.addLandmark(landmarkAt({2, 0, 1}, 0.1), unitDescriptor(1));
    const auto r = fuseAtOrigin(map, measurement({2, 0, 1}, 0.05, 9));  // E ≈ 2 > E0
    EXPECT_TRUE(r.created);
    // the new landmark: μ = z, Σ = R (line 34-35)
    const auto* lm = map.landmarks().find(r.id);
    ASSERT_NE(lm, nullptr);
    EXPECT_TRUE(lm->mean.isApprox(Eigen::Vector3d(2, 0, 1)));
    EXPECT_TRUE(lm->cov.isApprox(Eigen::Matrix3d::Identity() * 0.0025));
}

TEST(CVisualLandmarksMap, AFrameTakesALandmarkOnceWhenDistinct)
{
    // two points of one frame with the landmark's descriptor, both inside its gate: fused one
    // after the other both update it; with `distinct` the second is not offered it and starts
    // a landmark of its own
    for (const bool distinct : {false, true}) {
        CVisualLandmarksMap map;
        const uint32_t a = map.addLandmark(landmarkAt({2, 0, 1}, 0.1), unitDescriptor(1));
        const std::vector<TLandmarkMeasurement> z{measurement({2, 0.01, 1}, 0.05, 1),
                                                  measurement({2, 0.05, 1}, 0.05, 1)};
        std::vector<TMapMeasurement> in_map;
        std::vector<TMeasurementCandidates> candidates;
        for (const auto& m : z) {
            in_map.push_back(toMapFrame(m, {0, 0, 0}));
            candidates.push_back(map.findCandidates(m, in_map.back()));
        }
        const auto r =
            map.fuseFrame(z, in_map, candidates, 0,
                          distinct ? CVisualLandmarksMap::TFrameAssociation::DistinctInOrder
                                   : CVisualLandmarksMap::TFrameAssociation::OneByOne);
        ASSERT_EQ(r.size(), 2u);
        EXPECT_FALSE(r[0].created);
        EXPECT_EQ(r[0].id, a);
        EXPECT_EQ(r[1].created, distinct);
        EXPECT_EQ(r[1].id == a, !distinct);
        EXPECT_EQ(map.size(), distinct ? 2u : 1u);
        EXPECT_EQ(map.landmarks().find(a)->times_seen, distinct ? 2u : 3u);
    }
}

TEST(CVisualLandmarksMap, RemovesTheLandmarksSeenLessThanAsked)
{
    CVisualLandmarksMap map;
    std::vector<uint32_t> ids;
    for (unsigned n = 1; n <= 6; n++) {
        TVisualLandmark lm = landmarkAt({static_cast<double>(n), 0, 1}, 0.1);
        lm.times_seen = n;
        ids.push_back(map.addLandmark(lm, unitDescriptor(static_cast<int>(n))));
    }
    EXPECT_EQ(map.removeLandmarksSeenLessThan(1), 0u);
    EXPECT_EQ(map.removeLandmarksSeenLessThan(4), 3u);
    EXPECT_EQ(map.size(), 3u);
    for (size_t i = 0; i < ids.size(); i++)
        EXPECT_EQ(map.landmark(ids[i]) != nullptr, i + 1 >= 4) << "seen " << i + 1 << " times";
}

TEST(CVisualLandmarksMap, KnownCorrespondencesFollowTheIdentityNotTheGate)
{
    // associate_by_identity: a reading of identity 7 far outside the gate of 7's landmark goes
    // to it; a reading of identity 8 on top of that landmark starts 8's; an identity of −1
    // goes through the gate as before
    for (const bool by_identity : {false, true}) {
        SCOPED_TRACE(by_identity ? "by identity" : "by the gate");
        CVisualLandmarksMap map;
        map.insertionOptions.associate_by_identity = by_identity;
        map.insertionOptions.search_radius = 5;
        const auto reading = [](const Eigen::Vector3d& z, int64_t identity) {
            auto m = measurement(z, 0.05, 1);
            m.identity = identity;
            return m;
        };
        const auto first = fuseAtOrigin(map, reading({2, 0, 1}, 7));
        ASSERT_TRUE(first.created);
        const auto far = reading({2, 1.0, 1}, 7);
        const auto expected = map.evaluate(toMapFrame(far, {0, 0, 0}), first.id);
        EXPECT_GT(expected.D, map.insertionOptions.D0) << "the reading lies outside the gate";
        const auto second = fuseAtOrigin(map, far);
        EXPECT_EQ(second.created, !by_identity);
        EXPECT_EQ(second.id == first.id, by_identity);
        EXPECT_NEAR(second.log_w,
                    by_identity ? expected.log_likelihood : std::log(map.insertionOptions.p0),
                    1e-12)
            << "weighed by N(v; 0, Z) of its own landmark, or p0 for a new one";
        const size_t before = map.size();
        const auto other = fuseAtOrigin(map, reading({2, 0, 1}, 8));
        EXPECT_EQ(other.created, by_identity) << "identity 8 is another landmark";
        EXPECT_EQ(map.size(), before + (by_identity ? 1 : 0));
        const auto hidden = fuseAtOrigin(map, reading({2, 0, 1}, -1));
        EXPECT_FALSE(hidden.created) << "no identity: the gate associates it";
    }
}

TEST(CVisualLandmarksMap, KnownCorrespondencesGiveAnIdentityOneIdInEveryParticle)
{
    // two particles' maps share the pool; the one that meets identity 7 later starts its
    // landmark under the id the first one gave it
    auto pool = std::make_shared<LandmarkDescriptorPool>();
    CVisualLandmarksMap a(pool), b(pool);
    a.insertionOptions.associate_by_identity = b.insertionOptions.associate_by_identity = true;
    auto m = measurement({2, 0, 1}, 0.05, 1);
    m.identity = 7;
    const auto ra = fuseAtOrigin(a, m);
    fuseAtOrigin(a, measurement({3, 0, 1}, 0.05, 1));  // a landmark without identity
    m.z = {2.5, 0.3, 1};
    const auto rb = fuseAtOrigin(b, m);
    EXPECT_TRUE(ra.created);
    EXPECT_TRUE(rb.created);
    EXPECT_EQ(rb.id, ra.id);
    EXPECT_EQ(pool->landmarkOfIdentity(7), std::optional<uint32_t>(ra.id));
    EXPECT_FALSE(pool->landmarkOfIdentity(8).has_value());
}

TEST(CVisualLandmarksMap, EkfUpdateAndWeightMatchTheCameraFrameEquations)
{
    // Eq. 6-13 written in the sensor frame with g(x, l) = Rᵀ(l − t), G = Rᵀ, versus the map
    // frame update fuse() does, for a rotated robot and full covariances.
    CVisualLandmarksMap map;
    TVisualLandmark lm;
    lm.mean = {3.0, 1.0, 1.2};
    Eigen::Matrix3d A;
    A << 0.3, 0.1, 0.0, -0.05, 0.2, 0.07, 0.02, 0.01, 0.25;
    lm.cov = A * A.transpose();
    lm.times_seen = 1;
    const uint32_t id = map.addLandmark(lm, unitDescriptor(4));

    const mrpt::math::TPose2D robot(0.5, -0.3, 0.4);
    const double c = std::cos(robot.phi), s = std::sin(robot.phi);
    Eigen::Matrix3d Rot;
    Rot << c, -s, 0, s, c, 0, 0, 0, 1;
    const Eigen::Vector3d t(robot.x, robot.y, 0);
    TLandmarkMeasurement m;
    m.z = Rot.transpose() * (Eigen::Vector3d(3.1, 0.95, 1.25) - t);  // robot frame
    Eigen::Matrix3d B;
    B << 0.1, 0.02, 0.01, 0.0, 0.15, 0.03, 0.0, 0.0, 0.2;
    m.R = B * B.transpose();
    m.d = unitDescriptor(4);

    const Eigen::Matrix3d G = Rot.transpose();                                     // Eq. 7
    const Eigen::Vector3d z_hat = G * (lm.mean - t);                               // Eq. 6
    const Eigen::Matrix3d Z = G * lm.cov * G.transpose() + m.R;                    // Eq. 8
    const Eigen::Matrix3d K = lm.cov * G.transpose() * Z.inverse();                // Eq. 9
    const Eigen::Vector3d mu = lm.mean + K * (m.z - z_hat);                        // Eq. 10
    const Eigen::Matrix3d Sigma = (Eigen::Matrix3d::Identity() - K * G) * lm.cov;  // Eq. 11
    const Eigen::Vector3d v = m.z - z_hat;
    const double w = std::exp(-0.5 * v.dot(Z.inverse() * v)) /
                     std::sqrt((2 * M_PI * Z).determinant());  // Eq. 13

    const TMapMeasurement in_map = toMapFrame(m, robot);
    auto candidates = map.findCandidates(m, in_map);
    const auto r = map.fuse(m, in_map, candidates, 0);
    ASSERT_FALSE(r.created);
    EXPECT_EQ(r.id, id);
    EXPECT_NEAR(r.log_w, std::log(w), 1e-9);
    EXPECT_LT((map.landmarks().find(id)->mean - mu).norm(), 1e-12);
    EXPECT_LT((map.landmarks().find(id)->cov - Sigma).norm(), 1e-12);
}

namespace {
/// The points of a frame in the map frame (robot at the origin) and their shared candidates.
struct TFrame {
    std::vector<TMapMeasurement> in_map;
    std::vector<TMeasurementCandidates> candidates;
};
TFrame frameOf(const CVisualLandmarksMap& map, const std::vector<TLandmarkMeasurement>& z)
{
    TFrame f;
    for (const auto& m : z) {
        f.in_map.push_back(toMapFrame(m, {0, 0, 0}));
        f.candidates.push_back(map.findCandidates(m, f.in_map.back()));
    }
    return f;
}

/// `n_landmarks` landmarks (σ 0.03 m) and `n_points` points (σ 0.1 m) within 0.4 m of (2, 0, 1)
/// in `map`, their descriptors cycling through `descriptors` of them.
struct TRandomScene {
    std::vector<uint32_t> ids;
    std::vector<TLandmarkMeasurement> z;
};
TRandomScene randomScene(CVisualLandmarksMap& map, std::mt19937& gen, int n_landmarks, int n_points,
                         int descriptors)
{
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    TRandomScene scene;
    for (int l = 0; l < n_landmarks; l++)
        scene.ids.push_back(map.addLandmark(landmarkAt({2 + u(gen), u(gen), 1}, 0.03),
                                            unitDescriptor(1 + l % descriptors)));
    for (int j = 0; j < n_points; j++)
        scene.z.push_back(
            measurement({2 + u(gen), u(gen), 1 + 0.1 * u(gen)}, 0.1, 1 + j % descriptors));
    return scene;
}
}  // namespace

TEST(CVisualLandmarksMap, JointAssociationKeepsTwoNearbyLandmarksApart)
{
    // Two posts 0.2 m apart, read in one frame at y = 0.12 and y = 0.3 (σ 0.05 m). One by one,
    // the first reading takes the nearer post B and the second finds B taken and A outside its
    // gate: a new landmark. Jointly: first → A, second → B, no new landmark.
    CVisualLandmarksMap map;
    map.insertionOptions.E0 = 4;  // descriptors play no part here
    const uint32_t a = map.addLandmark(landmarkAt({2, 0, 1}, 0.01), unitDescriptor(1));
    const uint32_t b = map.addLandmark(landmarkAt({2, 0.2, 1}, 0.01), unitDescriptor(1));
    const auto f =
        frameOf(map, {measurement({2, 0.12, 1}, 0.05, 1), measurement({2, 0.3, 1}, 0.05, 1)});

    std::vector<uint32_t> taken;
    const auto first = map.associate(f.in_map[0], f.candidates[0], &taken);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->id, b);
    taken.push_back(first->id);
    EXPECT_FALSE(map.associate(f.in_map[1], f.candidates[1], &taken)) << "A is outside its gate";

    const auto joint = map.associateJointly(f.in_map, f.candidates);
    ASSERT_EQ(joint.size(), 2u);
    ASSERT_TRUE(joint[0] && joint[1]);
    EXPECT_EQ(joint[0]->id, a);
    EXPECT_EQ(joint[1]->id, b);
    const auto direct = map.evaluate(f.in_map[0], a);
    EXPECT_DOUBLE_EQ(joint[0]->log_likelihood, direct.log_likelihood);
    EXPECT_DOUBLE_EQ(joint[0]->D, direct.D);
}

TEST(CVisualLandmarksMap, JointAssociationMatchesBruteForce)
{
    // Random frames of 1-4 points among 1-5 landmarks: the joint association maximizes the sum
    // of log N(v; 0, Z) over gated pairs plus log p0 per new landmark, each landmark used once;
    // checked against enumerating every such assignment.
    std::mt19937 gen(7);
    for (int trial = 0; trial < 300; trial++) {
        CVisualLandmarksMap map;
        map.insertionOptions.E0 = 4;
        map.insertionOptions.p0 = 20 * (1 + trial % 3);
        const int n_landmarks = 1 + trial % 5, n_points = 1 + (trial / 5) % 4;
        const auto [ids, z] = randomScene(map, gen, n_landmarks, n_points, 1);
        const auto f = frameOf(map, z);

        // brute force: every landmark (or none) for each point, no landmark twice
        double best = -std::numeric_limits<double>::infinity();
        std::vector<int> choice(z.size(), -1);
        std::function<void(size_t, double)> enumerate = [&](size_t j, double sum) {
            if (j == z.size()) {
                best = std::max(best, sum);
                return;
            }
            choice[j] = -1;
            enumerate(j + 1, sum + std::log(map.insertionOptions.p0));
            for (int l = 0; l < n_landmarks; l++) {
                if (std::find(choice.begin(), choice.begin() + static_cast<long>(j), l) !=
                    choice.begin() + static_cast<long>(j))
                    continue;
                const auto a = map.evaluate(f.in_map[j], ids[static_cast<size_t>(l)]);
                if (a.D > map.insertionOptions.D0) continue;
                choice[j] = l;
                enumerate(j + 1, sum + a.log_likelihood);
            }
            choice[j] = -1;
        };
        enumerate(0, 0);

        const auto joint = map.associateJointly(f.in_map, f.candidates);
        ASSERT_EQ(joint.size(), z.size());
        double sum = 0;
        std::vector<uint32_t> used;
        for (size_t j = 0; j < z.size(); j++) {
            if (!joint[j]) {
                sum += std::log(map.insertionOptions.p0);
                continue;
            }
            EXPECT_LE(joint[j]->D, map.insertionOptions.D0);
            EXPECT_EQ(std::count(used.begin(), used.end(), joint[j]->id), 0) << "used twice";
            used.push_back(joint[j]->id);
            sum += joint[j]->log_likelihood;
        }
        EXPECT_NEAR(sum, best, 1e-9) << "trial " << trial;
    }
}

TEST(CVisualLandmarksMap, NearestFirstGivesALandmarkToItsNearestReading)
{
    // Post A mapped; in one frame a reading of a post not yet mapped, 0.25 m from A, comes
    // before A's own reading (σ 0.1 m, both inside A's gate). One by one the first takes A and
    // A's reading starts a landmark; nearest first, A's reading takes A and the other starts one.
    CVisualLandmarksMap map;
    map.insertionOptions.E0 = 4;
    const uint32_t a = map.addLandmark(landmarkAt({2, 0, 1}, 0.01), unitDescriptor(1));
    const std::vector<TLandmarkMeasurement> z{measurement({2, 0.25, 1}, 0.1, 1),
                                              measurement({2, 0.05, 1}, 0.1, 1)};
    const auto f = frameOf(map, z);
    std::vector<uint32_t> taken;
    const auto first = map.associate(f.in_map[0], f.candidates[0], &taken);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->id, a) << "the other post's reading is inside A's gate";

    const auto nearest = map.associateNearestFirst(z, f.in_map, f.candidates);
    ASSERT_EQ(nearest.size(), 2u);
    EXPECT_FALSE(nearest[0]);
    ASSERT_TRUE(nearest[1]);
    EXPECT_EQ(nearest[1]->id, a);
    const auto direct = map.evaluate(f.in_map[1], a);
    EXPECT_DOUBLE_EQ(nearest[1]->D, direct.D);
    EXPECT_DOUBLE_EQ(nearest[1]->log_likelihood, direct.log_likelihood);

    auto candidates = f.candidates;
    const auto in_order = CVisualLandmarksMap(map).fuseFrame(
        z, f.in_map, candidates, 0, CVisualLandmarksMap::TFrameAssociation::DistinctInOrder);
    EXPECT_EQ(in_order[0].id, a);
    EXPECT_TRUE(in_order[1].created);
    candidates = f.candidates;
    const auto fused = map.fuseFrame(z, f.in_map, candidates, 0,
                                     CVisualLandmarksMap::TFrameAssociation::DistinctNearestFirst);
    EXPECT_TRUE(fused[0].created);
    EXPECT_EQ(fused[1].id, a);
    EXPECT_FALSE(fused[1].created);
}

TEST(CVisualLandmarksMap, NearestFirstMatchesRepeatedArgmin)
{
    // Random frames of 1-5 points among 1-6 landmarks with 3 descriptors: against the rule
    // spelled out, the pair of smallest (E, D) among the points and landmarks left, inside the
    // gates, made one at a time; one point alone is associated as associate() does.
    std::mt19937 gen(11);
    for (int trial = 0; trial < 300; trial++) {
        CVisualLandmarksMap map;
        map.insertionOptions.E0 = 1.2;
        const int n_landmarks = 1 + trial % 6, n_points = 1 + (trial / 6) % 5;
        const auto [ids, z] = randomScene(map, gen, n_landmarks, n_points, 3);
        const auto f = frameOf(map, z);

        std::vector<std::optional<uint32_t>> expected(z.size());
        std::vector<bool> point_left(z.size(), true), landmark_left(ids.size(), true);
        for (;;) {
            std::optional<std::tuple<float, double, size_t, size_t>> best;
            for (size_t j = 0; j < z.size(); j++)
                for (size_t l = 0; l < ids.size(); l++) {
                    if (!point_left[j] || !landmark_left[l]) continue;
                    const float E = LandmarkDescriptorPool::squaredDistance(
                        z[j].d, map.descriptorPool().descriptor(ids[l]));
                    const double D = map.evaluate(f.in_map[j], ids[l]).D;
                    if (E > map.insertionOptions.E0 || D > map.insertionOptions.D0) continue;
                    const auto pair = std::make_tuple(E, D, j, l);
                    if (!best || pair < *best) best = pair;
                }
            if (!best) break;
            const auto [E, D, j, l] = *best;
            expected[j] = ids[l];
            point_left[j] = false;
            landmark_left[l] = false;
        }

        const auto nearest = map.associateNearestFirst(z, f.in_map, f.candidates);
        ASSERT_EQ(nearest.size(), z.size());
        for (size_t j = 0; j < z.size(); j++) {
            EXPECT_EQ(nearest[j].has_value(), expected[j].has_value()) << "trial " << trial;
            if (nearest[j] && expected[j]) {
                EXPECT_EQ(nearest[j]->id, *expected[j]);
            }
        }
        if (z.size() == 1) {
            const auto one = map.associate(f.in_map[0], f.candidates[0]);
            EXPECT_EQ(one.has_value(), nearest[0].has_value());
            if (one && nearest[0]) {
                EXPECT_EQ(one->id, nearest[0]->id);
            }
        }
    }
}

TEST(CVisualLandmarksMap, SerializesTheLandmarksOfIdentities)
{
    CVisualLandmarksMap map;
    map.insertionOptions.associate_by_identity = true;
    for (const int64_t identity : {9, 7}) {
        auto m = measurement({2.0 + identity, 0, 1}, 0.05, 1);
        m.identity = identity;
        fuseAtOrigin(map, m);
    }
    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << map;
    buf.Seek(0);
    CVisualLandmarksMap back;
    auto in = mrpt::serialization::archiveFrom(buf);
    in >> back;
    EXPECT_TRUE(back.insertionOptions.associate_by_identity);
    EXPECT_EQ(back.descriptorPool().identities(), map.descriptorPool().identities());
    EXPECT_EQ(back.descriptorPool().identities().size(), 2u);
    auto m = measurement({2.0 + 7, 0, 1}, 0.05, 1);
    m.identity = 7;
    EXPECT_EQ(fuseAtOrigin(back, m).id, *map.descriptorPool().landmarkOfIdentity(7));
}

// Versions 1-3 of the format carried each landmark's identity and its count of fused readings
// of other identities (evaluation state, now kept outside the map): such files still load.
TEST(CVisualLandmarksMap, ReadsVersion3MapsAndDropsTheirIdentityFields)
{
    CVisualLandmarksMap map;
    fuseAtOrigin(map, measurement({3, 1, 1}, 0.05, 1));
    fuseAtOrigin(map, measurement({3, 1, 1}, 0.05, 1), 1);
    fuseAtOrigin(map, measurement({5, -2, 1}, 0.05, 2));
    ASSERT_EQ(map.size(), 2u);

    // the body as version 3's serializeTo() wrote it
    mrpt::io::CMemoryStream body;
    auto out = mrpt::serialization::archiveFrom(body);
    const auto& io = map.insertionOptions;
    out << map.genericMapParams << io.D0 << io.E0 << io.p0 << io.search_radius << io.grid_cell_size
        << io.joint_association << io.associate_by_identity << map.renderOptions.draw_ellipsoids
        << map.renderOptions.ellipsoid_quantiles << map.renderOptions.point_size
        << static_cast<uint32_t>(map.size());
    map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        out << id;
        for (int i = 0; i < 3; i++) out << lm.mean[i];
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++) out << lm.cov(r, c);
        out << lm.times_seen << lm.seen_by << int64_t{7} << uint32_t{1};  // identity, conflicts
        for (const float v : map.descriptorPool().descriptor(id)) out << v;
        for (int i = 0; i < 3; i++) out << map.descriptorPool().creationPosition(id)[i];
    });
    out << uint32_t{0};  // no identities of known correspondences
    // the object's header and end flag as today's version writes them, with version 3
    mrpt::io::CMemoryStream current;
    mrpt::serialization::archiveFrom(current) << map;
    const auto bytesOf = [](const mrpt::io::CMemoryStream& s) {
        const auto* b = static_cast<const char*>(s.getRawBufferData());
        return std::string(b, b + s.getTotalBytesCount());
    };
    const std::string today = bytesOf(current);
    const std::string name = CVisualLandmarksMap::GetRuntimeClassIdStatic().className;
    const size_t version_at = today.find(name) + name.size();
    ASSERT_NE(today.find(name), std::string::npos);
    ASSERT_EQ(today[version_at], 4) << "the current version";
    const std::string v3 = today.substr(0, version_at) + char{3} + bytesOf(body) + today.back();
    EXPECT_EQ(v3.size(), today.size() + 12 * map.size()) << "an int64 and a uint32 per landmark";

    mrpt::io::CMemoryStream in_buf;
    in_buf.Write(v3.data(), v3.size());
    in_buf.Seek(0);
    CVisualLandmarksMap back;
    mrpt::serialization::archiveFrom(in_buf) >> back;
    ASSERT_EQ(back.size(), map.size());
    map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        const TVisualLandmark* b = back.landmark(id);
        ASSERT_NE(b, nullptr) << id;
        EXPECT_EQ(b->mean, lm.mean) << id;
        EXPECT_EQ(b->cov, lm.cov) << id;
        EXPECT_EQ(b->times_seen, lm.times_seen) << id;
        EXPECT_EQ(b->seen_by, lm.seen_by) << id;
        EXPECT_EQ(back.descriptorPool().descriptor(id), map.descriptorPool().descriptor(id));
    });
    // written again, it is today's file
    mrpt::io::CMemoryStream again;
    mrpt::serialization::archiveFrom(again) << back;
    EXPECT_EQ(bytesOf(again), today);
}

TEST(CVisualLandmarksMap, SerializesCreatesFromIniAndWritesMapTxt)
{
    mrpt::config::CConfigFileMemory ini(R"(
[Map]
visualLandmarksMap_count = 1
[Map_visualLandmarksMap_00_insertOpts]
D0 = 9.0
E0 = 0.3
p0 = 0.2
search_radius = 2.0
grid_cell_size = 0.5
joint_association = true
[Map_visualLandmarksMap_00_renderOpts]
draw_ellipsoids = false
)");
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(ini, "Map");
    mrpt::maps::CMultiMetricMap maps(inits);
    auto map = maps.mapByClass<CVisualLandmarksMap>();
    ASSERT_TRUE(map);
    EXPECT_DOUBLE_EQ(map->insertionOptions.D0, 9.0);
    EXPECT_DOUBLE_EQ(map->insertionOptions.E0, 0.3);
    EXPECT_TRUE(map->insertionOptions.joint_association);
    EXPECT_DOUBLE_EQ(map->descriptorPool().cellSize(), 0.5);
    for (int i = 0; i < 20; i++)
        fuseAtOrigin(*map, measurement({2.0 + i * 0.3, 0.1 * i, 1}, 0.05, 100 + i), i % 2);
    ASSERT_EQ(map->size(), 20u);

    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << maps;  // polymorphic, as particle copies and final_map.gz do
    buf.Seek(0);
    mrpt::maps::CMultiMetricMap back;
    auto in = mrpt::serialization::archiveFrom(buf);
    in >> back;
    auto read = back.mapByClass<CVisualLandmarksMap>();
    ASSERT_TRUE(read);
    ASSERT_EQ(read->size(), 20u);
    EXPECT_DOUBLE_EQ(read->insertionOptions.p0, 0.2);
    EXPECT_TRUE(read->insertionOptions.joint_association);
    map->landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        const auto* r = read->landmarks().find(id);
        ASSERT_NE(r, nullptr);
        EXPECT_EQ(r->mean, lm.mean);
        EXPECT_EQ(r->cov, lm.cov);
        EXPECT_EQ(r->seen_by, lm.seen_by);
        EXPECT_EQ(read->descriptorPool().descriptor(id), map->descriptorPool().descriptor(id));
    });
    // the read map associates like the original
    const auto again = fuseAtOrigin(*read, measurement({2.3, 0.1, 1}, 0.05, 101));
    EXPECT_FALSE(again.created);
    EXPECT_EQ(again.id, 1u);

    mrpt_vslam::test::ScratchFolder dir("visual_map_txt");
    map->saveMetricMapRepresentationToFile((dir.path() / "map").string());
    const auto file = mrpt_vslam::core::LandmarkFile::load((dir.path() / "map.txt").string());
    ASSERT_EQ(file.landmarks.size(), 20u);
    EXPECT_TRUE(file.landmarks[3].has_cov);
    EXPECT_NEAR(file.landmarks[3].position.x, 2.9, 1e-9);
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "map_descriptors.txt"));

    mrpt::opengl::CSetOfObjects scene;
    map->getVisualizationInto(scene);
    EXPECT_EQ(scene.size(), 1u) << "points only: draw_ellipsoids = false";
}

TEST(CVisualLandmarksMap, RejectsImpossibleOptions)
{
    // Checked on the options themselves: MRPT 2.5's TSetOfMetricMapInitializers leaks the map
    // definition when its loading throws (harmless in the apps, which then exit).
    const auto errorOf = [](const std::string& line) -> std::string {
        mrpt::config::CConfigFileMemory ini("[Map_visualLandmarksMap_00_insertOpts]\n" + line);
        CVisualLandmarksMap::TInsertionOptions o;
        try {
            o.loadFromConfigFile(ini, "Map_visualLandmarksMap_00_insertOpts");
        } catch (const std::exception& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(
        errorOf("E0 = -1").find("[Map_visualLandmarksMap_00_insertOpts] E0: must be in [0, 4]"),
        std::string::npos);
    EXPECT_NE(errorOf("D0 = 0").find("D0: must be finite and > 0"), std::string::npos);
    EXPECT_NE(errorOf("p0 = nan").find("p0: must be finite and > 0"), std::string::npos);
    EXPECT_NE(errorOf("grid_cell_size = -2").find("grid_cell_size"), std::string::npos);
    EXPECT_NE(errorOf("joint_association = true\nassociate_by_identity = true")
                  .find("associate_by_identity: cannot be combined with joint_association"),
              std::string::npos);
    EXPECT_EQ(errorOf("E0 = 0.7"), "");
}
