#!/usr/bin/env python3
# Where the fast soil particles are in CRM ParaView snapshots (soil_*.vtu of `terracal crm`):
# the fastest particles with their radial and vertical velocity, position relative to a vertical
# axis at (CX, CY), density, pressure and plastic strain, and the kinetic energy by region.
# Pure Python (the files are inline base64 Float32 arrays with UInt32 headers: core/vtu_writer).
# Usage: vtu_fastest.py CX CY SURFACE_Z SNAPSHOT.vtu [...]
import re, base64, struct, sys, math
def arrays(path):
    txt = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray type="Float32" Name="(\w+)" NumberOfComponents="(\d+)" format="binary">'
                         r'\s*([A-Za-z0-9+/=]+)\s*</DataArray>', txt):
        raw = base64.b64decode(m.group(3)); n = struct.unpack('<I', raw[:4])[0]
        vals = struct.unpack('<%df' % (n // 4), raw[4:4 + n])
        c = int(m.group(2)); out[m.group(1)] = [vals[i:i + c] for i in range(0, len(vals), c)]
    return out
def summary(path, cx, cy, surface):
    a = arrays(path); P = a['Points']; V = a['velocity']
    sp = [math.sqrt(v[0]**2 + v[1]**2 + v[2]**2) for v in V]
    idx = sorted(range(len(sp)), key=lambda i: -sp[i])[:15]
    # kinetic-energy share by region: radial distance r from the axis (bands sized for the 0.1 m plate
    # of results/plate_bin_check/h1.4/hold_cpu), depth below SURFACE_Z
    reg = {}
    ke = 0
    for p, s in zip(P, sp):
        r = math.hypot(p[0] - cx, p[1] - cy); z = surface - p[2]
        key = (('r<0.08' if r < 0.08 else 'r0.08-0.14' if r < 0.14 else 'r0.14-0.2' if r < 0.2 else 'r>0.2')
               + (' z<0.04' if z < 0.04 else ' z0.04-0.1' if z < 0.1 else ' z>0.1'))
        reg[key] = reg.get(key, 0) + s * s; ke += s * s
    print(path, 'fastest:', ' '.join('%.3f@(r%.3f,z%.3f)' % (sp[i], math.hypot(P[i][0]-cx, P[i][1]-cy), P[i][2])
                                     for i in idx[:8]))
    print('   KE share:', ', '.join('%s %.0f%%' % (k, 100 * v / ke)
                                    for k, v in sorted(reg.items(), key=lambda kv: -kv[1])[:6]))

def detail(path, cx, cy, n=10):
    a = arrays(path); P = a['Points']; V = a['velocity']; D = a['density']; PR = a['pressure']; PL = a['plastic_strain']
    sp = [math.sqrt(v[0]**2 + v[1]**2 + v[2]**2) for v in V]
    idx = sorted(range(len(sp)), key=lambda i: -sp[i])[:n]
    for i in idx:
        r = math.hypot(P[i][0]-cx, P[i][1]-cy)
        vr = ((P[i][0]-cx)*V[i][0] + (P[i][1]-cy)*V[i][1]) / max(r, 1e-9)
        print('  |v| %.3f v_r %+.3f v_z %+.3f  r %.3f z %.3f  rho %.0f p %.0f plastic %.3f'
              % (sp[i], vr, V[i][2], r, P[i][2], D[i][0], PR[i][0], PL[i][0]))


if __name__ == '__main__':
    if len(sys.argv) < 5:
        sys.exit('usage: vtu_fastest.py CX CY SURFACE_Z SNAPSHOT.vtu [...]')
    cx, cy, surface = map(float, sys.argv[1:4])
    for f in sys.argv[4:]:
        summary(f, cx, cy, surface)
        detail(f, cx, cy)
