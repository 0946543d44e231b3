#!/usr/bin/env bash
# Install the external toolchain of spherecontact on a fresh Debian 12 (bookworm) machine, as root.
# Idempotent: packages already installed are left as they are, the FreeFEM pref line is added once.
#   gmsh 4.8.4 (+ python3-gmsh), FreeFem++ 4.11 (+ libfreefem++ plugins: gmsh, iovtk),
#   dolfinx 0.5.2 for /usr/bin/python3, meshio 5 and h5py;
#   the DEM codes LAMMPS (Debian 20220106, "29 Sep 2021 - Update 2", GRANULAR built in) and
#   YADE 2023.02a (the lammps-* and yade-mindlin solvers), LIGGGHTS-PUBLIC 3.8.0 (liggghts, serial;
#   the liggghts-* solvers);
#   CalculiX ccx 2.20 (calculix-ccx, SPOOLES; the ccx-axisym solver), about 5 MB;
#   Kratos 10.4.4 with its DEMApplication (PyPI wheels, not a Debian package) in the project's own
#   virtual environment /opt/spherecontact/venv, made with Debian's /usr/bin/python3 (3.11):
#   the kratos-* solvers; with its Structural, ContactStructural and LinearSolvers applications (the
#   kratos-3d deck); about 70 MB, 20-30 s.
# Measured: ~245 packages, ~200 MB download, 2-3 minutes on a fresh machine (docs/toolchain.md);
# LAMMPS and YADE add 115 packages, 192 MB, about 2 minutes (docs/toolchain.md).
# Afterwards prints the versions found (the same facts as `spherecontact doctor`).
set -euo pipefail

PACKAGES=(gmsh python3-gmsh freefem++ libfreefem++ python3-dolfinx-real python3-meshio python3-h5py lammps yade liggghts calculix-ccx python3-venv)
export DEBIAN_FRONTEND=noninteractive
APT=(apt-get -y -q -o DPkg::Lock::Timeout=900 --no-install-recommends)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ "${#missing[@]}" -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  echo "setup.sh: installing ${missing[*]}"
  $SUDO apt-get -q -o DPkg::Lock::Timeout=900 update
  # Retry once: a first attempt once died with a dpkg "cannot stat … .deb" error and a retry passed.
  $SUDO "${APT[@]}" install "${missing[@]}" || {
    echo "setup.sh: apt-get install failed once; retrying"
    $SUDO apt-get -q -o DPkg::Lock::Timeout=900 update
    $SUDO "${APT[@]}" install "${missing[@]}"
  }
else
  echo "setup.sh: all packages already installed"
fi

# Debian's /etc/freefem++.pref points at /usr/lib/ff++/4.9/lib, but libfreefem++ installs the
# plugins (gmsh, iovtk) in /usr/lib/freefem++: add that load path once. spherecontact also sets
# FF_LOADPATH itself for every FreeFem++ run, so this line only helps people running decks by hand.
PREF=/etc/freefem++.pref
if [ -w "$PREF" ] || [ "$(id -u)" -eq 0 ]; then
  grep -qs '/usr/lib/freefem++' "$PREF" || echo 'loadpath += "/usr/lib/freefem++"' >> "$PREF"
fi

# Kratos: pinned wheels in the project's environment (the path is KRATOS_PYTHON's in
# crates/system/src/toolchain.rs); pip leaves an environment that already has them as it is.
KRATOS_VENV=/opt/spherecontact/venv
KRATOS_WHEELS=("KratosMultiphysics==10.4.4" "KratosDEMApplication==10.4.4"
  "KratosStructuralMechanicsApplication==10.4.4" "KratosContactStructuralMechanicsApplication==10.4.4"
  "KratosLinearSolversApplication==10.4.4")
[ -x "$KRATOS_VENV/bin/python" ] || /usr/bin/python3 -m venv "$KRATOS_VENV"
"$KRATOS_VENV/bin/pip" install -q --disable-pip-version-check "${KRATOS_WHEELS[@]}"

# Versions found (fail if a tool does not run).
echo "gmsh      $(command -v gmsh): $(gmsh -version 2>&1 | tail -n1)"
smoke=$(mktemp --suffix=.edp)
printf 'load "gmsh"\nload "iovtk"\ncout << "ffversion " << version << endl;\n' > "$smoke"
ffout=$(FF_LOADPATH=/usr/lib/freefem++ FreeFem++ -nw -ns -v 0 "$smoke" 2>&1) || { echo "$ffout"; rm -f "$smoke"; exit 1; }
rm -f "$smoke"
echo "FreeFem++ $(command -v FreeFem++): $(echo "$ffout" | sed -n 's/^ffversion //p') (plugins gmsh, iovtk load)"
/usr/bin/python3 -c "import dolfinx, gmsh, meshio, h5py; print('dolfinx  ', dolfinx.__version__, '(/usr/bin/python3); meshio', meshio.__version__, '; h5py', h5py.__version__, '; python gmsh', gmsh.__version__)"
lmpout=$(lmp -h 2>&1) || { echo "$lmpout" | tail -n 5; exit 1; }
echo "$lmpout" | grep -qw GRANULAR || { echo "setup.sh: lmp lacks the GRANULAR package"; exit 1; }
echo "LAMMPS    $(command -v lmp): $(echo "$lmpout" | sed -n 's/.*Simulator - //p' | head -n1) (GRANULAR package)"
echo "YADE      $(command -v yade): $(yade --version 2>&1 | sed -n 's/^Yade version: *//p')"
# liggghts -h prints its help and exits with code 1.
ligout=$(liggghts -h 2>&1) || true
echo "$ligout" | grep -q "Version LIGGGHTS" || { echo "setup.sh: liggghts does not report its version: $(echo "$ligout" | tail -n 3)"; exit 1; }
echo "LIGGGHTS  $(command -v liggghts): $(echo "$ligout" | sed -n 's/.*(Version \([^,)]*\).*/\1/p' | head -n1)"
ccxout=$(ccx -v 2>&1) || true
echo "$ccxout" | grep -q "Version" || { echo "setup.sh: ccx does not report its version: $ccxout"; exit 1; }
echo "CalculiX  $(command -v ccx): $(echo "$ccxout" | sed -n 's/.*Version *//p' | head -n1)"
kratosout=$(OMP_NUM_THREADS=1 "$KRATOS_VENV/bin/python" -c "import importlib.metadata as m, KratosMultiphysics.DEMApplication; print('kratosversion', m.version('KratosDEMApplication'))" 2>&1) \
  || { echo "$kratosout" | tail -n 5; exit 1; }
echo "Kratos    $KRATOS_VENV/bin/python: DEMApplication $(echo "$kratosout" | sed -n 's/^kratosversion //p')"
kratosout=$(OMP_NUM_THREADS=1 "$KRATOS_VENV/bin/python" -c "import importlib.metadata as m, KratosMultiphysics.StructuralMechanicsApplication, KratosMultiphysics.ContactStructuralMechanicsApplication, KratosMultiphysics.LinearSolversApplication; print('kratosversion', m.version('KratosContactStructuralMechanicsApplication'))" 2>&1) \
  || { echo "$kratosout" | tail -n 5; exit 1; }
echo "Kratos    $KRATOS_VENV/bin/python: ContactStructuralMechanicsApplication $(echo "$kratosout" | sed -n 's/^kratosversion //p') (with StructuralMechanics, LinearSolvers)"
