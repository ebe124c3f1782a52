#!/usr/bin/env python3
# A y-averaged x-z map of one field of a `terracal crm` soil snapshot (vtu/soil_*.vtu), one row per
# particle layer, over the strip footing's region (x 0.24-0.56 m, z 0.10-0.30 m in 2 cm cells;
# results/plate_bin_check, tenth study). Fields: vx, vz [mm/s], sxx, szz, sxz [kPa], rho [rho0].
# No numpy: the snapshot's base64 arrays are decoded with the standard library.
# Usage: vtu_field_map.py vtu/soil_00000210.vtu vx
import base64, re, struct, sys


def read_vtu(path):
    txt = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="([^"]+)"(?: NumberOfComponents="(\d+)")? format="(\w+)"[^>]*>'
                         r'\s*(.*?)\s*</DataArray>', txt, re.S):
        typ, name, nc, fmt, body = m.groups()
        nc = int(nc or 1)
        code = {'Float32': 'f', 'Float64': 'd', 'Int32': 'i', 'UInt8': 'B', 'Int64': 'q', 'UInt32': 'I'}[typ]
        if fmt == 'binary':  # a UInt32 byte count, then the data
            raw = base64.b64decode(body)
            n = struct.unpack('<I', raw[:4])[0]
            a = list(struct.unpack('<%d%s' % (n // struct.calcsize(code), code), raw[4:4 + n]))
        else:
            a = [float(x) for x in body.split()]
        out[name] = [a[i:i + nc] for i in range(0, len(a), nc)] if nc > 1 else a
    return out, txt


def main():
    path, what = sys.argv[1], sys.argv[2]
    d, txt = read_vtu(path)
    t = re.search(r'TimeValue.*?>\s*([\d.eE+-]+)', txt, re.S).group(1)
    print('t =', t, what)
    bins = {}
    for p, v, s, rho in zip(d['Points'], d['velocity'], d['stress'], d['density']):
        x, y, z = p
        if not (0.24 <= x < 0.56 and 0.10 <= z < 0.30):
            continue
        ix, iz = int((x - 0.24) / 0.02), int((z - 0.10) / 0.02)
        # stress components as written: xx, yy, zz, xy, yz, xz
        val = {'vx': v[0] * 1000, 'vz': v[2] * 1000, 'sxx': s[0] / 1000, 'szz': s[2] / 1000, 'sxz': s[5] / 1000,
               'rho': rho / 1700}[what]
        a = bins.setdefault((ix, iz), [0, 0])
        a[0] += val
        a[1] += 1
    for iz in reversed(range(10)):
        row = ['%6.1f' % (bins[(ix, iz)][0] / bins[(ix, iz)][1]) if (ix, iz) in bins else '     .' for ix in range(16)]
        print('%5.2f' % (0.10 + 0.02 * iz), ' '.join(row))
    print('x:   ', ' '.join('%6.2f' % (0.24 + 0.02 * ix) for ix in range(16)))


if __name__ == '__main__':
    main()
