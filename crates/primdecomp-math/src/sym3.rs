//! Symmetric 3×3 matrix stored as its six unique entries (§3.1's operator Q).

use super::vec3::V3;

/// Symmetric 3×3 matrix `[[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sym3 {
    pub xx: f64,
    pub xy: f64,
    pub xz: f64,
    pub yy: f64,
    pub yz: f64,
    pub zz: f64,
}

impl Sym3 {
    pub const ZERO: Sym3 = Sym3 {
        xx: 0.0,
        xy: 0.0,
        xz: 0.0,
        yy: 0.0,
        yz: 0.0,
        zz: 0.0,
    };

    /// `w · v vᵀ`.
    #[inline]
    pub fn outer(v: V3, w: f64) -> Sym3 {
        Sym3 {
            xx: w * v[0] * v[0],
            xy: w * v[0] * v[1],
            xz: w * v[0] * v[2],
            yy: w * v[1] * v[1],
            yz: w * v[1] * v[2],
            zz: w * v[2] * v[2],
        }
    }

    #[inline]
    pub fn add(&self, o: &Sym3) -> Sym3 {
        Sym3 {
            xx: self.xx + o.xx,
            xy: self.xy + o.xy,
            xz: self.xz + o.xz,
            yy: self.yy + o.yy,
            yz: self.yz + o.yz,
            zz: self.zz + o.zz,
        }
    }

    /// Full matrix, row-major.
    pub fn to_rows(self) -> [[f64; 3]; 3] {
        [
            [self.xx, self.xy, self.xz],
            [self.xy, self.yy, self.yz],
            [self.xz, self.yz, self.zz],
        ]
    }

    /// `M v`.
    #[cfg(test)]
    #[inline]
    pub fn mul_vec(&self, v: V3) -> V3 {
        [
            self.xx * v[0] + self.xy * v[1] + self.xz * v[2],
            self.xy * v[0] + self.yy * v[1] + self.yz * v[2],
            self.xz * v[0] + self.yz * v[1] + self.zz * v[2],
        ]
    }

    /// Largest absolute entry (used for scaling before iterating).
    pub fn max_abs(&self) -> f64 {
        self.xx
            .abs()
            .max(self.xy.abs())
            .max(self.xz.abs())
            .max(self.yy.abs())
            .max(self.yz.abs())
            .max(self.zz.abs())
    }
}
