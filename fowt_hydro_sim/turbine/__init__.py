"""The wind turbine on the platform (ROS-free, like ``physics``): a rigid rotor with thrust
and torque from Cp/Ct/Cq tables, a 1-DOF drivetrain, a blade-pitch actuator, wind inputs,
and NREL's ROSCO controller called through its Python interface."""
