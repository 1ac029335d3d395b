//! `STRATA_WINDOW`: where a client's window surfaces go, `"x,y,z"` or `"x,y,z,WxH"` (top left
//! corner in the output space, depth layer, and a size for windows the drop-in library cannot
//! measure). One parser for the drop-in library, which reads it, and `stratad run`, which sets
//! it.

/// The environment variable.
pub const ENV: &str = "STRATA_WINDOW";

/// A parsed `STRATA_WINDOW`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowPlacement {
    /// Left edge in the output space.
    pub x: i32,
    /// Top edge in the output space.
    pub y: i32,
    /// Depth layer.
    pub z: f32,
    /// Size, for windows the library cannot measure.
    pub size: Option<(i32, i32)>,
}

/// A `STRATA_WINDOW` value that does not parse.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{ENV}={0:?}: expected \"x,y,z\" or \"x,y,z,WxH\" (integers, a finite z, a positive size)")]
pub struct BadPlacement(pub String);

impl std::str::FromStr for WindowPlacement {
    type Err = BadPlacement;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || BadPlacement(s.to_string());
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        let (x, y, z) = match parts.as_slice() {
            [x, y, z] | [x, y, z, _] => {
                (x.parse().map_err(|_| bad())?, y.parse().map_err(|_| bad())?, z.parse::<f32>().map_err(|_| bad())?)
            }
            _ => return Err(bad()),
        };
        if !z.is_finite() {
            return Err(bad());
        }
        let size = match parts.get(3) {
            Some(wh) => {
                let (w, h) = wh.split_once(['x', 'X']).ok_or_else(bad)?;
                let (w, h): (i32, i32) = (w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?);
                if w <= 0 || h <= 0 {
                    return Err(bad());
                }
                Some((w, h))
            }
            None => None,
        };
        Ok(WindowPlacement { x, y, z, size })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placement_parses_position_depth_and_size() {
        let p = |s: &str| s.parse::<WindowPlacement>().ok();
        assert_eq!(p("10,20,0.5"), Some(WindowPlacement { x: 10, y: 20, z: 0.5, size: None }));
        assert_eq!(p("0, 0, 1, 320x240"), Some(WindowPlacement { x: 0, y: 0, z: 1.0, size: Some((320, 240)) }));
        for bad in ["1,2", "1,2,nan", "1,2,3,0x5", "1,2,3,4", "a,2,3"] {
            assert_eq!(p(bad), None, "{bad}");
        }
    }
}
