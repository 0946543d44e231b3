# Written before every YADE script by spherecontact (crates/external/src/dem/yade.rs, `job`): a run leaves nothing
# outside its own run folder. YADE makes its temporary folder /tmp/yade-XXXXXX as it starts (the
# name is fixed in its Omega: TMPDIR is not read) and, run with -x, never removes it; the scripts
# never use it (no O.tmpFilename() file), so it goes first. Only an empty folder yade-… is removed.
import os as _spherecontact_os

from yade import O as _spherecontact_O

_spherecontact_tmp = _spherecontact_os.path.dirname(_spherecontact_O.tmpFilename())
if _spherecontact_os.path.basename(_spherecontact_tmp).startswith("yade-"):
    _spherecontact_os.rmdir(_spherecontact_tmp)
del _spherecontact_os, _spherecontact_O, _spherecontact_tmp
