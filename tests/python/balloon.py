"""The balloon, the droplet the defaults were before the calibration (results/calibration/balloon.toml),
which the tests of the machinery run on the small scenes laid out for it (as tests/balloon.hpp)."""

# Keyword arguments of softdrop.DropletParams, optimize and sweep, and the same on the command line.
DROPLET = dict(nrt=1.5e9, ks=119755.0, kd=365.0, cc=2e4, dt=2e-5, viscosity=3000.0, viscosity_dilation=1.0)
GRAINS = dict(r_min=8.0, r_max=16.0)
ARGS = ["--nrt", "1.5e9", "--ks", "119755", "--kd", "365", "--cc", "2e4", "--dt", "2e-5", "--viscosity", "3000",
        "--viscosity-dilation", "1", "--r-min", "8", "--r-max", "16"]
