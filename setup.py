"""Packaging for fowt_hydro_sim.

Works both as a ROS 2 ament_python package (colcon build) and as a plain
pip-installable project on a machine without ROS:

    pip install .            # core simulator and bag tools (numpy, scipy, pyyaml, numba, mcap)
    pip install '.[ros]'     # + rclpy and message packages as PyPI wheels (the main job)
    pip install '.[ros,plots,cluster]'   # + figures (matplotlib) and Dask for sweeps and fits
    pip install '.[ros,dev]'   # + tests, docs and linter (what CI installs)
"""
from setuptools import find_packages, setup

package_name = 'fowt_hydro_sim'

ROS_WHEELS = [
    'ros-rclpy',
    'ros-rmw-fastrtps-cpp',
    'ros-geometry-msgs',
    'ros-nav-msgs',
    'ros-rosgraph-msgs',
    'ros-std-msgs',
    'ros-builtin-interfaces',
]

ROSCO = 'rosco>=2.10,<2.11'
DOCS = ['mkdocs>=1.6', 'mkdocs-material>=9.5', 'mkdocstrings[python]>=0.26']
PLOTS = ['matplotlib']
CLUSTER = ['dask[distributed]']
# the mooring lines' models: MoorPy's quasi-static catenary and MoorDyn-C's lumped-mass lines
MOORING = ['moordyn>=2.7,<2.8', 'moorpy']
# every command's extras, and the tests' independent references: bag readers, OpenFAST's file
# library, ROSCO's simulator (the turbine's oracle), MoorPy, capytaine (BEM)
# fowt-sim measured import of HDF5 files (CSV/TSV and MATLAB .mat need no extra)
BASIN = ['h5py']
TEST = [*PLOTS, *CLUSTER, *MOORING, *BASIN, 'pytest', 'pytest-xdist', 'mcap-ros2-support', 'rosbags',
        'openfast-io>=5.0', ROSCO, 'capytaine>=3.0']

# Top-level packages are listed explicitly so that a missing directory is a loud
# build error (find_packages would silently skip it); sub-packages are found.
TOP_LEVEL = [package_name, 'msg_adapters']
PACKAGES = sorted(set(TOP_LEVEL) | set(find_packages(include=[p + '.*' for p in TOP_LEVEL])))

setup(
    name=package_name,
    version='0.1.0',
    description='Floating offshore wind turbine platform hydrodynamics simulator '
                'with ROS 2 interfaces',
    license='Apache-2.0',
    maintainer='fowt_hydro_sim maintainers',
    maintainer_email='fowt-dev@example.com',
    python_requires='>=3.10',
    packages=PACKAGES,
    package_data={package_name: ['physics/data/*.yaml', 'physics/data/**/*', 'turbine/data/*.yaml',
                                  'turbine/data/systems/*.yaml', 'studies/diagnosis/independent/data/*',
                                  'rosbag/msg/**/*']},
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        # `ros2 run fowt_hydro_sim node|controller` (colcon); named apart from console scripts
        # so that pip does not put a `node` in <venv>/bin
        ('lib/' + package_name, ['scripts/node', 'scripts/controller', 'scripts/play', 'scripts/record']),
    ],
    install_requires=[
        'numpy',
        'scipy',
        'pyyaml',
        'numba',
        'mcap>=1.2',
        'zstandard',
        'tqdm',
    ],
    extras_require={
        # the ROS 2 nodes and bag tools: rclpy and the message packages as PyPI wheels
        'ros': ROS_WHEELS,
        # the figures of analyze, load-cases, calibrate, diagnose and the turbine plots
        'plots': PLOTS,
        # sweep, calibrate, diagnose and diagnose-benchmark run on a local or remote Dask cluster
        'cluster': CLUSTER,
        # mooring model moorpy (quasi-static catenary) and moordyn (MoorDyn-C's lumped-mass lines)
        'mooring': MOORING,
        # NREL's ROSCO with its Python toolbox (tuning, its own simulator). The turbine node needs
        # only the compiled controller and its files: `pip install --no-deps 'rosco>=2.10,<2.11'`
        # gives those without the toolbox's WISDEM (the package's metadata requires it)
        'rosco': [ROSCO],
        'test': TEST,
        # the documentation site
        'docs': DOCS,
        # everything a contributor runs: the tests, the docs build and the linter
        'dev': [*TEST, 'ruff', *DOCS],
        # fowt-sim platform import (OpenFAST HydroDyn decks)
        'hydrodyn': ['openfast-io>=5.0'],
        # rebuilding the independent simulator's BEM database (the stored one needs neither)
        'bem': ['capytaine>=3.0', 'xarray'],
        # fowt-sim measured import: HDF5 basin files
        'basin': BASIN,
        # diagnose-benchmark --source independent: the catenary mooring scenario (MoorPy's catenary)
        'benchmark': ['moorpy'],
    },
    zip_safe=False,
    entry_points={
        'console_scripts': [
            'fowt-sim = fowt_hydro_sim.cli:main',
        ],
    },
)
