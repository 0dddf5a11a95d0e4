#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/LandmarkIdentityTally.h>
#include <mrpt_vslam/multirobot/TeamPathSmoother.h>
#include <mrpt_vslam/test/SyntheticTeamWorld.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

using namespace mrpt_vslam::multirobot;
using mrpt_vslam::test::positionError;
using mrpt_vslam::test::standardFilter;
using mrpt_vslam::test::SyntheticTeamWorld;

namespace {
/// The message loading `[TeamPathSmoother]` with `lines` throws, "" if it loads.
std::string errorOf(const std::string& lines)
{
    mrpt::config::CConfigFileMemory ini("[TeamPathSmoother]\n" + lines);
    TeamPathSmoother::TOptions o;
    try {
        o.loadFromConfigFile(ini, "TeamPathSmoother");
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

/// The odometry of a robot that drives 20 steps of 0.2 m along x, turns round on the spot and
/// drives 20 steps back (σ 1 cm and 0.5° per step): steps 1 to 20 out, 21 the turn.
std::vector<mrpt_vslam::core::TOdometryGaussian> outAndBack()
{
    mrpt_vslam::core::TOdometryGaussian forward, turn;
    forward.mean.x = 0.2;
    forward.cov = Eigen::Vector3d(1e-4, 1e-4, std::pow(0.5 * M_PI / 180, 2)).asDiagonal();
    turn.mean.phi = M_PI;
    turn.cov = forward.cov;
    std::vector<mrpt_vslam::core::TOdometryGaussian> u(20, forward);
    u.push_back(turn);
    u.insert(u.end(), 20, forward);
    return u;
}

/// `smoother` set to smooth (map_along_path, smooth_paths) a run from `start`.
void startSmoothing(TeamPathSmoother& smoother, const std::vector<mrpt::math::TPose2D>& start)
{
    smoother.options.map_along_path = true;
    smoother.options.smooth_paths = true;
    smoother.onReset(start, 0, 0);
}
}  // namespace

// With one particle and the filter's own gate, the map made again along the particle's path
// is the particle's map: same landmarks, means, covariances and counts (a pose taken from the
// wrong step of the path would move them), made with the same correspondences; the count
// threshold then removes exactly the landmarks seen fewer times.
TEST(TeamPathSmoother, MapAlongPathWithTheFiltersGateIsTheParticlesMap)
{
    SyntheticTeamWorld::TParams wp;
    wp.landmarks = 300;
    SyntheticTeamWorld world(wp);
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 1, 7);
    TeamPathSmoother smoother(CVisualLandmarksMap{});
    EXPECT_THROW(smoother.mapAlongPath(TTeamParticle()), std::logic_error);
    smoother.options.D0 = CVisualLandmarksMap().insertionOptions.D0;
    filter.setStepObserver(&smoother);
    filter.reset(world.startPoses(), world.time);
    auto pf = standardFilter();
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CSensoryFrame sf;
    for (int i = 0; i < 30; i++) {
        world.step(acts, sf);
        if (i % 3 == 1) sf.eraseByLabel("R2_LANDMARKS");  // steps where one robot sees nothing
        pf.executeOn(filter, &acts, &sf);
    }
    const auto& p = filter.bestParticle();
    std::vector<TCorrespondence> correspondences;
    const CVisualLandmarksMap rebuilt = smoother.mapAlongPath(p, &correspondences);
    ASSERT_GT(p.map.size(), 20u);
    ASSERT_EQ(rebuilt.size(), p.map.size());
    std::vector<unsigned> times_seen;
    p.map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        const TVisualLandmark* r = rebuilt.landmark(id);
        ASSERT_NE(r, nullptr) << id;
        EXPECT_LT((r->mean - lm.mean).norm(), 1e-9) << id;
        EXPECT_LT((r->cov - lm.cov).norm(), 1e-12) << id;
        EXPECT_EQ(r->times_seen, lm.times_seen) << id;
        EXPECT_EQ(r->seen_by, lm.seen_by) << id;
        times_seen.push_back(lm.times_seen);
    });
    const auto history = TLandmarkIdentityTally::historyOf(p);
    ASSERT_EQ(correspondences.size(), history.size());
    for (size_t i = 0; i < history.size(); i++) {
        EXPECT_EQ(correspondences[i].robot, history[i].robot) << i;
        EXPECT_EQ(correspondences[i].landmark, history[i].landmark) << i;
        EXPECT_EQ(correspondences[i].track_id, history[i].track_id) << i;
    }
    smoother.options.min_seen_fraction = 0.05;
    const unsigned threshold = smoother.minTimesSeen();
    const auto kept = static_cast<size_t>(std::count_if(
        times_seen.begin(), times_seen.end(), [&](unsigned n) { return n >= threshold; }));
    ASSERT_GT(kept, 0u);
    ASSERT_LT(kept, p.map.size());
    EXPECT_EQ(smoother.mapAlongPath(p, &correspondences).size(), kept);
    for (const auto& c : correspondences)
        EXPECT_GE(p.map.landmark(c.landmark)->times_seen, threshold);

    // a new run: what was recorded is forgotten, the old particle's path no longer fits
    const TTeamParticle before = p;
    filter.reset(world.startPoses(), world.time);
    EXPECT_THROW(smoother.mapAlongPath(before), std::logic_error);
}

// The count threshold is relative to the run: of 100 frames with landmark measurements (two
// steps without any and one with a reading of a robot only do not count), landmarks read in
// 100, 60, 7 and 1 of them; a fraction f keeps those read in at least ceil(100 f) frames.
TEST(TeamPathSmoother, MinSeenFractionRemovesTheLandmarksReadInFewerFrames)
{
    TeamPathSmoother smoother(CVisualLandmarksMap{});
    const std::vector<mrpt::math::TPose2D> start{{0, 0, 0}, {0, -5, 0}};
    smoother.onReset(start, 0, 0);
    const std::vector<Eigen::Vector3d> at{{2, 0, 0}, {0, 2, 0}, {-2, 0, 0}, {0, -2, 0}};
    const std::vector<size_t> frames_read{100, 60, 7, 1};
    auto measurement = [](const Eigen::Vector3d& z) {
        TLandmarkMeasurement m;
        m.z = z;
        m.R = Eigen::Matrix3d::Identity() * 1e-4;
        return m;
    };
    TTeamParticle p;
    p.path.append(0, teamPoses(start));
    const size_t frames = 100, steps = frames + 3;
    for (size_t step = 1; step <= steps; step++) {
        std::vector<TLandmarkMeasurement> z;
        std::vector<CMultiRobotVisualSLAM::TRobotReading> readings;
        if (step <= frames) {
            for (size_t l = 0; l < at.size(); l++)
                if (step <= frames_read[l]) z.push_back(measurement(at[l]));
        } else if (step == frames + 1) {
            readings.push_back({1, measurement({0, -5, 0})});
        }
        smoother.onRobotStep(step, 0, mrpt_vslam::core::TOdometryGaussian(), z, readings);
        smoother.onRobotStep(step, 1, mrpt_vslam::core::TOdometryGaussian(), {}, {});
        p.path.append(static_cast<double>(step), teamPoses(start));
    }
    auto keptCounts = [&](double fraction) {
        smoother.options.min_seen_fraction = fraction;
        std::multiset<unsigned> counts;
        smoother.mapAlongPath(p).landmarks().forEach(
            [&](uint32_t, const TVisualLandmark& lm) { counts.insert(lm.times_seen); });
        return counts;
    };
    using Counts = std::multiset<unsigned>;
    EXPECT_EQ(keptCounts(0), (Counts{1, 7, 60, 100}));
    EXPECT_EQ(smoother.minTimesSeen(), 0u);
    EXPECT_EQ(keptCounts(0.07), (Counts{7, 60, 100}));  // 0.07 × 100 rounds to 7.000000000000001
    EXPECT_EQ(smoother.minTimesSeen(), 7u);
    EXPECT_EQ(keptCounts(0.071), (Counts{60, 100}));
    EXPECT_EQ(smoother.minTimesSeen(), 8u);
    EXPECT_EQ(keptCounts(0.6), (Counts{60, 100}));
    EXPECT_EQ(keptCounts(0.601), (Counts{100}));
    EXPECT_EQ(keptCounts(1), (Counts{100}));
}

// Post A read alone, then in one frame a reading of post B (not yet mapped, 0.25 m from A,
// inside A's gate) before A's own reading. In the order of the readings B's takes A and A's
// starts a landmark of its own; nearest pair first, each landmark gets the readings of one post.
TEST(TeamPathSmoother, NearestPairFirstGivesEachLandmarkTheReadingsOfOnePost)
{
    TeamPathSmoother smoother(CVisualLandmarksMap{});
    const std::vector<mrpt::math::TPose2D> start{{0, 0, 0}};
    smoother.onReset(start, 0, 0);
    auto reading = [](const Eigen::Vector3d& z, int64_t post) {
        TLandmarkMeasurement m;
        m.z = z;
        m.R = Eigen::Matrix3d::Identity() * 0.01;
        m.track_id = post;
        return m;
    };
    const std::vector<std::vector<TLandmarkMeasurement>> frames{
        {reading({2, 0, 0}, 0)}, {reading({2, 0.25, 0}, 1), reading({2, 0.05, 0}, 0)}};
    TTeamParticle p;
    p.path.append(0, teamPoses(start));
    for (size_t step = 1; step <= frames.size(); step++) {
        smoother.onRobotStep(step, 0, mrpt_vslam::core::TOdometryGaussian(), frames[step - 1], {});
        p.path.append(static_cast<double>(step), teamPoses(start));
    }
    for (const bool nearest : {false, true}) {
        smoother.options.nearest_pair_first = nearest;
        std::vector<TCorrespondence> c;
        EXPECT_EQ(smoother.mapAlongPath(p, &c).size(), 2u);
        ASSERT_EQ(c.size(), 3u);
        std::map<uint32_t, std::set<int64_t>> posts;
        for (const auto& r : c) posts[r.landmark].insert(r.track_id);
        const auto mixed = std::count_if(posts.begin(), posts.end(),
                                         [](const auto& l) { return l.second.size() > 1; });
        EXPECT_EQ(mixed, nearest ? 0 : 1) << "nearest_pair_first = " << nearest;
    }
}

// reanchorAfterGaps() through smoothPaths(), from particles whose paths are the true ones: R2
// sees nothing for 15 s; its part after that gap, displaced by 0.4 m and 20 deg, is put back
// onto its odometry, and the true paths are left alone. (With descriptors least squares alone
// recovers the part here too; the case it does not, readings gone to wrong landmarks on the
// MRCLAM data, is in doc/real-data.md.)
TEST(TeamPathSmoother, SmoothingReanchorsAPartDisplacedAfterAGap)
{
    SyntheticTeamWorld::TParams wp;
    wp.landmarks = 300;
    SyntheticTeamWorld world(wp);
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 1, 5);
    TeamPathSmoother smoother(CVisualLandmarksMap{});  // records frames and odometry
    smoother.options.map_along_path = true;
    smoother.options.min_seen_fraction = 0.025;
    smoother.options.smooth_paths = true;
    filter.setStepObserver(&smoother);
    filter.reset(world.startPoses(), world.time);
    auto pf = standardFilter();
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CSensoryFrame sf;
    const size_t steps = 60, gapFrom = 20, gapTo = 35;  // R2 blind in steps [gapFrom, gapTo)
    TTeamParticle truth, displaced;
    truth.path.append(world.time, teamPoses(world.startPoses()));
    displaced.path = truth.path;
    const mrpt::poses::CPose2D by(0.3, -0.3, 20 * M_PI / 180);
    mrpt::poses::CPose2D at;  // R2's true pose after the gap
    for (size_t i = 1; i <= steps; i++) {
        world.step(acts, sf);
        if (i >= gapFrom && i < gapTo) sf.eraseByLabel("R2_LANDMARKS");
        pf.executeOn(filter, &acts, &sf);
        truth.path.append(world.time, teamPoses(world.truth));
        auto poses = world.truth;
        if (i == gapTo) at = mrpt::poses::CPose2D(poses[1]);
        if (i >= gapTo) poses[1] = (at + by + (mrpt::poses::CPose2D(poses[1]) - at)).asTPose();
        displaced.path.append(world.time, teamPoses(poses));
    }
    // R2's error after the gap
    auto errorAfterGap = [&](const TeamPathSmoother::TSmoothedTeam& s) {
        const auto t = CMultiRobotVisualSLAM::pathOf(truth, 1);
        double se = 0;
        for (size_t i = gapTo; i <= steps; i++)
            se += std::pow(positionError(s.paths[1][i].second, t[i].second), 2);
        return std::sqrt(se / static_cast<double>(steps + 1 - gapTo));
    };
    const auto plain = smoother.smoothPaths(displaced);
    smoother.options.reanchor_gap = 10;
    const auto reanchored = smoother.smoothPaths(displaced);
    const auto undisplaced = smoother.smoothPaths(truth);
    EXPECT_EQ(plain.reanchored, 0u);
    EXPECT_EQ(reanchored.reanchored, 1u);
    EXPECT_EQ(undisplaced.reanchored, 0u);
    EXPECT_LT(errorAfterGap(undisplaced), 0.2);
    EXPECT_LT(errorAfterGap(reanchored), errorAfterGap(undisplaced) + 0.01);
    // the correspondences of the smoothed map are those of each of its landmarks' readings
    std::map<uint32_t, uint32_t> readings;
    for (const auto& c : reanchored.correspondences) readings[c.landmark]++;
    EXPECT_EQ(readings.size(), reanchored.map.size());
    reanchored.map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        EXPECT_EQ(readings[id], lm.times_seen) << id;
    });
}

// A robot stands for ten steps (odometry increments of exactly zero, with a noise floor of
// 1 cm and 1 deg) reading four posts 3 m away, each frame's readings shifted by ±2 cm as if
// read from elsewhere; then drives 0.2 m by odometry to where the readings put it at 0.23 m.
// With zero_odometry_stands_still the standing poses stay at the start, whatever the readings
// say; without, they follow the readings. The moving step still follows its readings.
TEST(TeamPathSmoother, ZeroOdometryTiesTheStandingPosesToTheStart)
{
    TeamPathSmoother smoother(CVisualLandmarksMap{});
    const std::vector<mrpt::math::TPose2D> start{{0, 0, 0}};
    startSmoothing(smoother, start);
    const std::vector<Eigen::Vector2d> posts{{3, 0}, {0, 3}, {-3, 0}, {0, -3}};
    auto readingsFrom = [&](const Eigen::Vector2d& at) {
        std::vector<TLandmarkMeasurement> z;
        for (const auto& post : posts) {
            TLandmarkMeasurement m;
            m.z << post - at, 0;
            m.R = Eigen::Matrix3d::Identity() * 1e-4;
            z.push_back(m);
        }
        return z;
    };
    mrpt_vslam::core::TOdometryGaussian still;
    still.cov = Eigen::Vector3d(1e-4, 1e-4, std::pow(M_PI / 180, 2)).asDiagonal();
    mrpt_vslam::core::TOdometryGaussian forward = still;
    forward.mean.x = 0.2;
    TTeamParticle p;
    p.path.append(0, teamPoses(start));
    const size_t standing = 10;
    for (size_t step = 1; step <= standing; step++) {
        const double shift = step % 2 ? 0.02 : -0.02;
        smoother.onRobotStep(step, 0, still, readingsFrom({shift, shift}), {});
        p.path.append(static_cast<double>(step), teamPoses(start));
    }
    smoother.onRobotStep(standing + 1, 0, forward, readingsFrom({0.23, 0}), {});
    p.path.append(static_cast<double>(standing + 1), teamPoses({{0.2, 0, 0}}));

    auto farthestStanding = [&](const TeamPathSmoother::TSmoothedTeam& s) {
        double d = 0;
        for (size_t step = 1; step <= standing; step++)
            d = std::max(d, positionError(s.paths[0][step].second, start[0]));
        return d;
    };
    const auto tied = smoother.smoothPaths(p);
    smoother.options.zero_odometry_stands_still = false;
    const auto unbound = smoother.smoothPaths(p);
    EXPECT_LT(farthestStanding(tied), 0.005);
    EXPECT_GT(farthestStanding(unbound), 0.02);
    EXPECT_GT(tied.paths[0][standing + 1].second.x, 0.215);
}

// A robot drives 4 m along x and back (odometry with 1 cm and 0.5 deg per step), reading four
// posts 2 m off its line (1 cm) and, within 0.6 m, a post 0.15 m off it (1 mm): on the way back
// those close readings put that post 2 cm from where the way out put it, about the step's
// odometry noise. Mapped along the path with the readings' own covariance, the close post
// splits in two; with reassociate (each reading widened by its step's odometry covariance,
// later rounds starting from the landmarks solved before) it stays one, between the two.
TEST(TeamPathSmoother, ReassociationKeepsAPostReadFromCloseByOnTwoPassesOne)
{
    TeamPathSmoother smoother(CVisualLandmarksMap{});
    const std::vector<mrpt::math::TPose2D> start{{0, 0, 0}};
    startSmoothing(smoother, start);
    const std::vector<Eigen::Vector2d> far{{1, 2}, {3, 2}, {1, -2}, {3, -2}};
    const Eigen::Vector2d close(2, 0.15);
    auto readingsFrom = [&](const mrpt::math::TPose2D& x, const Eigen::Vector2d& closeAt) {
        const mrpt::poses::CPose2D pose(x);
        std::vector<TLandmarkMeasurement> z;
        auto add = [&](const Eigen::Vector2d& post, double std) {
            double lx = 0, ly = 0;
            pose.inverseComposePoint(post.x(), post.y(), lx, ly);
            TLandmarkMeasurement m;
            m.z << lx, ly, 0;
            m.R = Eigen::Matrix3d::Identity() * std * std;
            z.push_back(m);
        };
        for (const auto& post : far) add(post, 0.01);
        if ((closeAt - Eigen::Vector2d(x.x, x.y)).norm() < 0.6) add(closeAt, 0.001);
        return z;
    };
    TTeamParticle p;
    p.path.append(0, teamPoses(start));
    mrpt::poses::CPose2D x(start[0]);
    const auto motions = outAndBack();
    for (size_t step = 1; step <= motions.size(); step++) {
        x = x + mrpt::poses::CPose2D(motions[step - 1].mean);
        const Eigen::Vector2d closeAt = step <= 21 ? close : close + Eigen::Vector2d(0, 0.02);
        smoother.onRobotStep(step, 0, motions[step - 1], readingsFrom(x.asTPose(), closeAt), {});
        p.path.append(static_cast<double>(step), teamPoses({x.asTPose()}));
    }

    auto nearClose = [&](const CVisualLandmarksMap& map) {
        std::vector<Eigen::Vector2d> near;
        map.landmarks().forEach([&](uint32_t, const TVisualLandmark& lm) {
            if ((lm.mean.head<2>() - close).norm() < 0.1) near.push_back(lm.mean.head<2>());
        });
        return near;
    };
    const auto split = smoother.smoothPaths(p);
    EXPECT_EQ(split.map.size(), 6u);
    EXPECT_EQ(nearClose(split.map).size(), 2u);
    smoother.options.reassociate = true;
    const auto joined = smoother.smoothPaths(p);
    EXPECT_EQ(joined.map.size(), 5u);
    const auto one = nearClose(joined.map);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_GT(one[0].y(), close.y());
    EXPECT_LT(one[0].y(), close.y() + 0.02);
}

// Twelve posts 0.7 m apart in two rows, read (σ 3 cm, uniform noise of ±5 cm) within 2.5 m on
// the way out and back; the best particle's way back is 0.3 m off. With reassociate, the first
// round's map along that path holds the posts twice and the second round starts from both
// copies, which then share the readings and lower that round's cost (by about 300 of 680); the
// output map, made afresh along the smoothed path, holds each post once. The cost given is the
// output's: brute force over its path, each reading at the output landmark nearest to it.
TEST(TeamPathSmoother, TheCostIsThatOfTheOutputPathAndMap)
{
    TeamPathSmoother smoother(CVisualLandmarksMap{});
    const std::vector<mrpt::math::TPose2D> start{{0, 0, 0}};
    startSmoothing(smoother, start);
    smoother.options.reassociate = true;
    std::vector<Eigen::Vector2d> posts;
    for (int i = 0; i < 6; i++) {
        posts.emplace_back(0.7 * i, 1.0);
        posts.emplace_back(0.7 * i + 0.35, -1.0);
    }
    uint32_t draw = 1;  // a fixed linear congruential sequence in [-1, 1]
    auto noise = [&] {
        draw = draw * 1103515245u + 12345u;
        return static_cast<double>((draw >> 8) % 2001) / 1000.0 - 1.0;
    };
    auto readingsFrom = [&](const mrpt::poses::CPose2D& pose) {
        std::vector<TLandmarkMeasurement> z;
        for (const auto& post : posts) {
            double lx = 0, ly = 0;
            pose.inverseComposePoint(post.x(), post.y(), lx, ly);
            if (std::hypot(lx, ly) > 2.5) continue;
            TLandmarkMeasurement m;
            m.z << lx + 0.05 * noise(), ly + 0.05 * noise(), 0;
            m.R = Eigen::Matrix3d::Identity() * 0.03 * 0.03;
            z.push_back(m);
        }
        return z;
    };
    TTeamParticle p;
    p.path.append(0, teamPoses(start));
    mrpt::poses::CPose2D x(start[0]);
    const auto motions = outAndBack();
    std::vector<std::vector<TLandmarkMeasurement>> readings;
    for (size_t step = 1; step <= motions.size(); step++) {
        x = x + mrpt::poses::CPose2D(motions[step - 1].mean);
        readings.push_back(readingsFrom(x));
        smoother.onRobotStep(step, 0, motions[step - 1], readings.back(), {});
        mrpt::math::TPose2D particle = x.asTPose();
        if (step >= 21) particle.y += 0.3;
        p.path.append(static_cast<double>(step), teamPoses({particle}));
    }

    const auto out = smoother.smoothPaths(p);
    EXPECT_EQ(out.map.size(), posts.size());
    const auto& path = out.paths.at(0);
    const Eigen::Vector3d e0(path[0].second.x, path[0].second.y, path[0].second.phi);
    double cost = e0.squaredNorm() / 1e-6;  // the start's prior, σ 1e-3
    for (size_t s = 1; s < path.size(); s++) {
        const auto& u = motions[s - 1];
        const mrpt::poses::CPose2D pose(path[s].second);
        const mrpt::poses::CPose2D d = pose - mrpt::poses::CPose2D(path[s - 1].second);
        const Eigen::Vector3d e(d.x() - u.mean.x, d.y() - u.mean.y,
                                mrpt::math::wrapToPi(d.phi() - u.mean.phi));
        cost += e.dot(u.cov.inverse() * e);
        for (const auto& m : readings[s - 1]) {
            double gx = 0, gy = 0, lx = 0, ly = 0, best = 1e9;
            pose.composePoint(m.z.x(), m.z.y(), gx, gy);
            Eigen::Vector2d nearest;
            out.map.landmarks().forEach([&](uint32_t, const TVisualLandmark& lm) {
                const double dist = (lm.mean.head<2>() - Eigen::Vector2d(gx, gy)).norm();
                if (dist < best) best = dist, nearest = lm.mean.head<2>();
            });
            pose.inverseComposePoint(nearest.x(), nearest.y(), lx, ly);
            const Eigen::Vector2d r = m.z.head<2>() - Eigen::Vector2d(lx, ly);
            const double r2 = r.dot(m.R.topLeftCorner<2, 2>().inverse() * r);
            cost += r2 <= 9 ? r2 : 6 * std::sqrt(r2) - 9;  // Huber, 3σ
        }
    }
    EXPECT_NEAR(out.cost, cost, 1e-6 * cost);
}

TEST(TeamPathSmoother, OptionsLoadFromTheirSectionAndRejectImpossibleValues)
{
    mrpt::config::CConfigFileMemory ini(R"([TeamPathSmoother]
map_along_path = true
D0 = 20
min_seen_fraction = 0.05
nearest_pair_first = true
smooth_paths = true
rounds = 3
huber = 2
odometry_scale_std = 0.3
motion_cov_factor = 0.5
zero_odometry_stands_still = false
reanchor_gap = 10
reanchor_gain = 0.2
reassociate = true
)");
    TeamPathSmoother::TOptions o;
    o.loadFromConfigFile(ini, "TeamPathSmoother");
    EXPECT_TRUE(o.map_along_path);
    EXPECT_EQ(o.D0, 20);
    EXPECT_EQ(o.min_seen_fraction, 0.05);
    EXPECT_TRUE(o.nearest_pair_first);
    EXPECT_TRUE(o.smooth_paths);
    EXPECT_EQ(o.rounds, 3u);
    EXPECT_EQ(o.huber, 2);
    EXPECT_EQ(o.odometry_scale_std, 0.3);
    EXPECT_EQ(o.motion_cov_factor, 0.5);
    EXPECT_FALSE(o.zero_odometry_stands_still);
    EXPECT_EQ(o.reanchor_gap, 10);
    EXPECT_EQ(o.reanchor_gain, 0.2);
    EXPECT_TRUE(o.reassociate);
    // what saveToConfigFile() writes loads back the same
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "TeamPathSmoother");
    TeamPathSmoother::TOptions back;
    back.loadFromConfigFile(saved, "TeamPathSmoother");
    EXPECT_EQ(back.min_seen_fraction, 0.05);
    EXPECT_EQ(back.rounds, 3u);
    EXPECT_EQ(back.reanchor_gain, 0.2);
    EXPECT_TRUE(back.smooth_paths);
    EXPECT_TRUE(back.nearest_pair_first);
    EXPECT_FALSE(back.zero_odometry_stands_still);
    EXPECT_TRUE(back.reassociate);

    EXPECT_EQ(errorOf(""), "") << "the defaults are valid";
    EXPECT_NE(errorOf("D0 = 0").find("[TeamPathSmoother] D0: must be > 0"), std::string::npos);
    EXPECT_NE(errorOf("min_seen_fraction = -0.1").find("min_seen_fraction: must be in [0, 1]"),
              std::string::npos);
    EXPECT_NE(errorOf("min_seen_fraction = 1.5").find("min_seen_fraction: must be in [0, 1]"),
              std::string::npos);
    EXPECT_NE(errorOf("min_times_seen = 150")
                  .find("[TeamPathSmoother] min_times_seen: replaced by min_seen_fraction"),
              std::string::npos);
    EXPECT_NE(errorOf("smooth_paths = true").find("smooth_paths: needs map_along_path = true"),
              std::string::npos);
    EXPECT_NE(errorOf("rounds = 0").find("rounds: must be 1 to 100"), std::string::npos);
    EXPECT_NE(errorOf("rounds = 1000000").find("rounds: must be 1 to 100"), std::string::npos);
    EXPECT_NE(errorOf("huber = -1").find("huber: must be >= 0"), std::string::npos);
    EXPECT_NE(errorOf("odometry_scale_std = -0.1").find("odometry_scale_std: must be >= 0"),
              std::string::npos);
    EXPECT_NE(errorOf("motion_cov_factor = 0").find("motion_cov_factor: must be > 0"),
              std::string::npos);
    EXPECT_NE(errorOf("reanchor_gap = -1").find("reanchor_gap: must be >= 0"), std::string::npos);
    EXPECT_NE(errorOf("map_along_path = true\nreassociate = true")
                  .find("reassociate: needs smooth_paths = true"),
              std::string::npos);
    EXPECT_NE(errorOf("reanchor_gain = 1").find("reanchor_gain: must be in (0, 1)"),
              std::string::npos);
}
