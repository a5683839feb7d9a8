"""fowt_hydro_sim: a floating offshore wind platform simulator (strip-theory Morison
hydrodynamics, 6-DOF rigid body) with ROS 2 interfaces. The model never imports rclpy."""
__version__ = "0.1.0"
