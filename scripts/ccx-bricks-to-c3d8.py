# The 8-node counterpart of a ccx-3d deck on 20-node bricks (docs/external-decks.md, "Kratos 3D:
# known failures", the bricks at c_max/4): CalculiX's C3D8 on the corners of the same bricks, the
# mesh kratos-3d's hex8 element runs on. Run it in a folder that `spherecontact deck write CASE
# --solver ccx-3d DIR` wrote for a case with `[calculix] element = "hex20"`:
#     cd DIR && python3 ccx-bricks-to-c3d8.py && OMP_NUM_THREADS=1 ccx -i job
# It rewrites job.inp in place: each *ELEMENT block of TYPE=C3D20 becomes TYPE=C3D8 with each
# element's first 8 nodes (C3D20 lists its corners first, in C3D8's order); the mid-side nodes
# stay, unconnected (CalculiX gives them no degrees of freedom). The faces S1-S6 of the contact
# surfaces are numbered alike for both elements. The reactions are in job.dat, the iterations in
# job.sta; `spherecontact deck read` does not read the result (it expects the 20-node bricks).
import sys

lines = open("job.inp").read().split("\n")
out, i, converted = [], 0, 0
while i < len(lines):
    line = lines[i]
    i += 1
    if not line.upper().startswith("*ELEMENT") or "TYPE=C3D20," not in line.upper().replace(" ", ""):
        out.append(line)
        continue
    out.append(line.replace("C3D20R", "C3D8").replace("C3D20", "C3D8"))
    numbers = []
    while i < len(lines) and not lines[i].startswith("*"):
        numbers += [x for x in lines[i].replace(" ", "").split(",") if x]
        i += 1
        while len(numbers) >= 21:
            out.append(", ".join(numbers[:9]))
            numbers = numbers[21:]
            converted += 1
    if numbers:
        sys.exit("job.inp: an element of a C3D20 block has %d numbers, not 21" % len(numbers))
if converted == 0:
    sys.exit("job.inp: no *ELEMENT block of TYPE=C3D20 (write the deck with [calculix] element = \"hex20\")")
open("job.inp", "w").write("\n".join(out))
print("job.inp: %d elements now C3D8" % converted)
