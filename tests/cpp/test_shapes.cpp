// One shape vocabulary: Shape descriptions in Obstacles, Scene and a robot's visuals.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>
#include <fcl/fcl.h>

#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/simulation.hpp"

using namespace octoreach;

namespace {

Pose tilted(const Eigen::Vector3d& at) {
  Pose T = Pose::Identity();
  T.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = at;
  return T;
}

// A box's 12 triangles in the world frame.
void box_triangles(const Eigen::Vector3d& size, const Pose& T, std::vector<Eigen::Vector3d>& v,
                   std::vector<Eigen::Vector3i>& f) {
  for (int i = 0; i < 8; ++i)
    v.push_back(T * Eigen::Vector3d((i & 4 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(),
                                    (i & 1 ? 0.5 : -0.5) * size.z()));
  f = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
       {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
}

}  // namespace

TEST(Shapes, TiltedBoxCastsAsItsTriangles) {
  const Eigen::Vector3d size(0.4, 0.2, 0.3), centre(0.3, -0.2, 0.5);
  Scene solid, mesh;
  solid.add(Shape::box(size, tilted(centre)));
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  box_triangles(size, tilted(centre), v, f);
  mesh.add_mesh(v, f);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.5, 1.5), near(-0.2, 0.2);
  int hits = 0;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d o = centre + Eigen::Vector3d(u(rng), u(rng), u(rng));
    if (solid.solid(o)) continue;
    const Eigen::Vector3d d = (centre + Eigen::Vector3d(near(rng), near(rng), near(rng)) - o).normalized();
    double ta, tb;
    Eigen::Vector3d na, nb;
    const bool a = solid.raycast(o, d, 4.0, ta, &na), b = mesh.raycast(o, d, 4.0, tb, &nb);
    ASSERT_EQ(a, b);
    if (!a) continue;
    ++hits;
    EXPECT_NEAR(ta, tb, 1e-9);
    EXPECT_LT((na - nb).norm(), 1e-6);
  }
  EXPECT_GT(hits, 100);
}

TEST(Shapes, SceneObstaclesHoldEveryShape) {
  Scene s;
  s.add_box({0, 0, 0}, {1, 1, 1});
  s.add(Shape::sphere(0.2, tilted({2, 0, 0})));
  s.add(Shape::cylinder(0.1, 0.5, tilted({3, 0, 0})));
  s.add(Shape::box({0.2, 0.2, 0.2}, tilted({4, 0, 0})));
  s.add_mesh({{5, 0, 0}, {6, 0, 0}, {5, 1, 0}}, {{0, 1, 2}});
  const Obstacles o = s.obstacles();
  ASSERT_EQ(o.size(), 5u);
  const char* kinds[] = {"box", "sphere", "cylinder", "box", "mesh"};
  for (std::size_t i = 0; i < 5; ++i) EXPECT_STREQ(o.shapes()[i].type_name(), kinds[i]);
  for (double x : {0.5, 2.0, 3.0, 4.0}) {
    Pose at = Pose::Identity();
    at.translation() = Eigen::Vector3d(x, x < 1 ? 0.5 : 0.0, x < 1 ? 0.5 : 0.0);
    EXPECT_TRUE(o.collides_box(Eigen::Vector3d::Constant(0.01), at)) << x;
    EXPECT_TRUE(s.solid(at.translation())) << x;
  }
  // Both queries refuse a pose that is not a rigid transform (a scaled one would place the box elsewhere).
  Pose scaled = Pose::Identity();
  scaled.linear() *= 2.0;
  fcl::Boxd small(0.01, 0.01, 0.01);
  small.computeLocalAABB();
  EXPECT_THROW(o.collides_box(Eigen::Vector3d::Constant(0.01), scaled), std::invalid_argument);
  try {
    o.collides(small, scaled);
    ADD_FAILURE() << "a scaled pose was answered";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("collides: pose is not a rigid transform"), std::string::npos) << e.what();
  }
  fcl::CollisionObjectd stretched(std::make_shared<fcl::Boxd>(0.01, 0.01, 0.01), fcl::Transform3d(scaled.matrix()));
  stretched.computeAABB();
  EXPECT_THROW(o.collides(stretched), std::invalid_argument);
  Scene copy;
  copy.add(o);  // Obstacles -> Scene -> Obstacles keeps every shape
  EXPECT_EQ(copy.shapes().size(), 5u);
  EXPECT_EQ(copy.triangle_count(), 1u);
}

TEST(Shapes, DescribesFclGeometry) {
  EXPECT_EQ(Shape::of(std::make_shared<fcl::Boxd>(1, 2, 3), Pose::Identity()).size, Eigen::Vector3d(1, 2, 3));
  const Shape c = Shape::of(std::make_shared<fcl::Cylinderd>(0.1, 0.4), Pose::Identity());
  EXPECT_EQ(c.type, Shape::Type::Cylinder);
  EXPECT_DOUBLE_EQ(c.length, 0.4);
  EXPECT_THROW(Shape::of(std::make_shared<fcl::Capsuled>(0.1, 0.4), Pose::Identity()), std::invalid_argument);
  EXPECT_THROW(Shape::box({1, 0, 1}), std::invalid_argument);
}

TEST(Shapes, RobotVisualsAndSource) {
  const std::string urdf = R"(<robot name="r">
    <material name="blue"><color rgba="0 0 1 1"/></material>
    <link name="a"><visual><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.1" length="0.2"/></geometry>
      <material name="blue"/></visual>
      <visual><geometry><mesh filename="package://nowhere/m.stl"/></geometry></visual>
      <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
    <link name="b"/>
    <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>)";
  auto robot = Robot::from_urdf(urdf);
  const auto& visuals = robot->links()[0].visuals;
  ASSERT_EQ(visuals.size(), 2u);
  EXPECT_EQ(visuals[0].shape.type, Shape::Type::Cylinder);
  EXPECT_DOUBLE_EQ(visuals[0].shape.origin.translation().z(), 0.1);
  ASSERT_TRUE(visuals[0].rgba.has_value());
  EXPECT_EQ((*visuals[0].rgba)[2], 1.0);
  EXPECT_EQ(visuals[1].mesh_uri, "package://nowhere/m.stl");  // not found: kept, without a file
  EXPECT_EQ(visuals[1].shape.mesh_path, "");
  EXPECT_FALSE(visuals[1].shape.geometry);
  EXPECT_TRUE(robot->links()[1].visuals.empty());
  EXPECT_EQ(robot->source().urdf, "");  // given as XML text
  auto from_file = Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
  EXPECT_EQ(from_file->source().urdf, std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
}
