//! The wall-ink network (issue 26): a small convolutional network that reads P(wall) of every
//! pixel of a plan drawing, trained on the CPU ([`super::net_train`]) on the same drawings as
//! the forest ([`super::model`]). Where the forest sees a pixel through a filter bank of at
//! most σ = 14 working pixels, the network sees about 250 pixels around it (a U-Net: two
//! stride-2 steps, dilated convolutions at a quarter and an eighth of the resolution, skips
//! back to the full resolution), so the edges stay sharp and more of a wall's surroundings
//! decide whether it is one.
//!
//! The weights are a safetensors file (`crates/plan/models/wall_net.safetensors`, about
//! 216 kB, compiled into the binary); its metadata holds one key, [`HEADER_KEY`], whose value is
//! the [`NetHeader`] as JSON (one key, because safetensors writes its metadata map in hash
//! order and a retrained file must come out byte for byte the same).

use std::collections::HashMap;

use candle_core::{DType, Device, Module, Tensor};
use candle_nn::{Conv2d, Conv2dConfig, VarBuilder, conv2d};
use image::GrayImage;

use super::model::{ModelError, Working, normalise, working_size};

/// Version of the network file; a file of another version is refused.
pub const NET_FORMAT: u32 = 1;

/// The metadata key of the network file's [`NetHeader`].
pub const HEADER_KEY: &str = "castellan";

/// What the network file says of itself besides its weights.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NetHeader {
    pub format: u32,
    /// [`Working::max_side`] of the drawings it was trained on.
    pub max_side: u32,
    /// How it was trained (seed, steps, sources).
    pub provenance: String,
}

/// The network shipped with castellan.
pub const SHIPPED_NET: &[u8] = include_bytes!("../../models/wall_net.safetensors");

/// Channels at a quarter and an eighth of the resolution.
const DEEP: usize = 24;

/// The layers, by the names their weights carry in the file.
pub(crate) struct Unet {
    e1: Conv2d,
    d1: Conv2d,
    e2: Conv2d,
    d2: Conv2d,
    quarter: Vec<Conv2d>,
    d3: Conv2d,
    eighth: Vec<Conv2d>,
    u4: Conv2d,
    u2: Conv2d,
    u1: Conv2d,
    out: Conv2d,
}

fn conv3(
    vb: &VarBuilder,
    name: &str,
    (from, to): (usize, usize),
    stride: usize,
    dilation: usize,
) -> candle_core::Result<Conv2d> {
    let cfg = Conv2dConfig {
        padding: dilation,
        stride,
        dilation,
        ..Default::default()
    };
    conv2d(from, to, 3, cfg, vb.pp(name))
}

impl Unet {
    /// The layers over `vb`: a new network when it is backed by a `VarMap`, a trained one when
    /// by the file's tensors.
    pub(crate) fn new(vb: &VarBuilder) -> candle_core::Result<Unet> {
        let quarter = [1, 2, 4, 8]
            .iter()
            .enumerate()
            .map(|(i, &d)| conv3(vb, &format!("c{i}"), (DEEP, DEEP), 1, d))
            .collect::<candle_core::Result<_>>()?;
        let eighth = [2, 4]
            .iter()
            .enumerate()
            .map(|(i, &d)| conv3(vb, &format!("c8{i}"), (DEEP, DEEP), 1, d))
            .collect::<candle_core::Result<_>>()?;
        Ok(Unet {
            e1: conv3(vb, "e1", (1, 8), 1, 1)?,
            d1: conv3(vb, "d1", (8, 16), 2, 1)?,
            e2: conv3(vb, "e2", (16, 16), 1, 1)?,
            d2: conv3(vb, "d2", (16, DEEP), 2, 1)?,
            quarter,
            d3: conv3(vb, "d3", (DEEP, DEEP), 2, 1)?,
            eighth,
            u4: conv3(vb, "u4", (2 * DEEP, 16), 1, 1)?,
            u2: conv3(vb, "u2", (32, 8), 1, 1)?,
            u1: conv3(vb, "u1", (16, 4), 1, 1)?,
            out: conv2d(4, 1, 1, Default::default(), vb.pp("out"))?,
        })
    }

    /// Logits of P(wall), `[batch, 1, h, w]`, of ink-ness `[batch, 1, h, w]` (1 − normalised
    /// grey); `h` and `w` multiples of 8.
    pub(crate) fn forward(&self, x: &Tensor) -> candle_core::Result<Tensor> {
        let full = self.e1.forward(x)?.relu()?;
        let half = self.e2.forward(&self.d1.forward(&full)?.relu()?)?.relu()?;
        let mut quarter = self.d2.forward(&half)?.relu()?;
        for c in &self.quarter {
            quarter = c.forward(&quarter)?.relu()?;
        }
        let mut eighth = self.d3.forward(&quarter)?.relu()?;
        for c in &self.eighth {
            eighth = c.forward(&eighth)?.relu()?;
        }
        let up = |t: &Tensor, like: &Tensor| -> candle_core::Result<Tensor> {
            let (_, _, h, w) = like.dims4()?;
            t.upsample_nearest2d(h, w)
        };
        let q = self
            .u4
            .forward(&Tensor::cat(&[&quarter, &up(&eighth, &quarter)?], 1)?)?
            .relu()?;
        let h = self
            .u2
            .forward(&Tensor::cat(&[&half, &up(&q, &half)?], 1)?)?
            .relu()?;
        let f = self
            .u1
            .forward(&Tensor::cat(&[&full, &up(&h, &full)?], 1)?)?
            .relu()?;
        self.out.forward(&f)
    }
}

/// A trained wall-ink network.
pub struct WallNet {
    pub(crate) net: Unet,
    /// The resolution it reads the drawing at (the forest's).
    pub working: Working,
    /// How it was trained (seed, steps, sources), for the report.
    pub provenance: String,
}

impl std::fmt::Debug for WallNet {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WallNet")
            .field("working", &self.working)
            .field("provenance", &self.provenance)
            .finish_non_exhaustive()
    }
}

/// The drawing as the network reads it: ink-ness at the working size, padded with paper to a
/// multiple of 8 (`[1, 1, ph, pw]`), and the working size.
pub(crate) fn input(grey: &GrayImage, working: &Working) -> (Vec<f32>, usize, usize) {
    let (w, h) = grey.dimensions();
    let (ws, hs) = working_size(w, h, working);
    let norm = normalise(grey);
    let g = if (ws, hs) == (w, h) {
        norm
    } else {
        image::imageops::resize(&norm, ws, hs, image::imageops::FilterType::Triangle)
    };
    let x = g.pixels().map(|p| 1.0 - f32::from(p[0]) / 255.0).collect();
    (x, ws as usize, hs as usize)
}

impl WallNet {
    /// Reads and checks a network file (format and every layer's shape).
    pub fn from_bytes(bytes: &[u8]) -> Result<WallNet, ModelError> {
        let decode = |e: String| ModelError::Decode(format!("network: {e}"));
        let (_, meta) =
            safetensors::SafeTensors::read_metadata(bytes).map_err(|e| decode(e.to_string()))?;
        let header: NetHeader = meta
            .metadata()
            .as_ref()
            .and_then(|m| m.get(HEADER_KEY))
            .ok_or_else(|| decode(format!("no \"{HEADER_KEY}\" header")))
            .and_then(|h| serde_json::from_str(h).map_err(|e| decode(e.to_string())))?;
        if header.format != NET_FORMAT {
            return Err(ModelError::Invalid(format!(
                "network file has format {}, this program reads format {NET_FORMAT}",
                header.format
            )));
        }
        if header.max_side < 16 {
            return Err(ModelError::Invalid(format!(
                "network file: working side {}",
                header.max_side
            )));
        }
        let tensors: HashMap<String, Tensor> =
            candle_core::safetensors::load_buffer(bytes, &Device::Cpu)
                .map_err(|e| decode(e.to_string()))?;
        let vb = VarBuilder::from_tensors(tensors, DType::F32, &Device::Cpu);
        let net = Unet::new(&vb).map_err(|e| ModelError::Invalid(format!("network: {e}")))?;
        Ok(WallNet {
            net,
            working: Working {
                enlarge_below: 0,
                max_side: header.max_side,
            },
            provenance: header.provenance,
        })
    }

    /// The network that ships with castellan.
    pub fn shipped() -> Result<WallNet, ModelError> {
        WallNet::from_bytes(SHIPPED_NET)
    }

    /// P(wall) of every pixel of `grey` (one class) at the resolution `working` gives.
    fn wall_map(&self, grey: &GrayImage, working: &Working) -> pixelclass::Probabilities {
        let (x, w, h) = input(grey, working);
        let data = self
            .logits(&x, w, h)
            .iter()
            .map(|&z| 1.0 / (1.0 + (-z).exp()))
            .collect();
        pixelclass::Probabilities {
            width: w,
            height: h,
            classes: 1,
            data,
        }
    }

    /// P(not wall) and P(wall) of every pixel of `grey` at the resolution `working` gives (a
    /// forest's), as the forest's maps are laid out: the context of the user's strokes
    /// ([`super::refine`]).
    pub fn two_class_map(&self, grey: &GrayImage, working: &Working) -> pixelclass::Probabilities {
        let wall = self.wall_map(grey, working);
        pixelclass::Probabilities {
            classes: 2,
            data: wall.data.iter().flat_map(|&p| [1.0 - p, p]).collect(),
            ..wall
        }
    }

    /// P(wall) of every pixel of `grey`, at `out_w` × `out_h` (the drawing's size or a
    /// multiple of it).
    pub fn wall_probability(&self, grey: &GrayImage, out_w: u32, out_h: u32) -> Vec<f32> {
        let map = self.wall_map(grey, &self.working);
        pixelclass::resample::enlarge(&map, out_w as usize, out_h as usize).data
    }

    /// Logits of the `w` × `h` ink-ness image `x`.
    fn logits(&self, x: &[f32], w: usize, h: usize) -> Vec<f32> {
        let (pw, ph) = (w.div_ceil(8) * 8, h.div_ceil(8) * 8);
        let mut padded = vec![0f32; pw * ph];
        for y in 0..h {
            padded[y * pw..y * pw + w].copy_from_slice(&x[y * w..(y + 1) * w]);
        }
        let run = || -> candle_core::Result<Vec<f32>> {
            let t = Tensor::from_vec(padded, (1, 1, ph, pw), &Device::Cpu)?;
            self.net.forward(&t)?.flatten_all()?.to_vec1::<f32>()
        };
        let z = run().expect("a checked network reads any padded image");
        let mut out = vec![0f32; w * h];
        for y in 0..h {
            out[y * w..(y + 1) * w].copy_from_slice(&z[y * pw..y * pw + w]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_network_reads_and_a_broken_file_is_refused() {
        let net = WallNet::shipped().unwrap();
        assert_eq!(net.working.max_side, 1200);
        assert!(!net.provenance.is_empty());
        assert!(SHIPPED_NET.len() < 400_000, "{} bytes", SHIPPED_NET.len());
        for bad in [
            &SHIPPED_NET[..SHIPPED_NET.len() / 2],
            &b"not a network"[..],
            &[],
        ] {
            assert!(WallNet::from_bytes(bad).is_err());
        }
        // A file of another format is refused by name.
        let key = br#"\"format\":1"#;
        let at = SHIPPED_NET
            .windows(key.len())
            .position(|w| w == key)
            .expect("the format is in the header");
        let mut other = SHIPPED_NET.to_vec();
        other[at + key.len() - 1] = b'9';
        let e = WallNet::from_bytes(&other).unwrap_err().to_string();
        assert!(e.contains("format 9"), "{e}");
    }
}
