//! Training the wall-ink network ([`super::net`]) on the CPU: random crops of the training
//! drawings at the working resolution (most centred on a wall pixel, flipped and transposed,
//! their ink darkened or lightened), a weighted logistic loss that skips the ignored pixels,
//! AdamW. Deterministic from the seed: the weights start from a seeded stream (candle's CPU
//! device cannot be seeded), and the crops come from another.

use candle_core::{DType, Device, Tensor};
use candle_nn::{AdamW, Optimizer, ParamsAdamW, VarBuilder, VarMap};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::model::Working;
use super::net::{HEADER_KEY, NET_FORMAT, NetHeader, Unet, WallNet, input};
use super::paint::{IGNORE, WALL};
use super::train::Sheet;

/// Training settings.
#[derive(Debug, Clone, PartialEq)]
pub struct NetParams {
    pub seed: u64,
    pub steps: usize,
    /// Crops per step.
    pub batch: usize,
    /// Side of a crop (working pixels; a multiple of 8).
    pub crop: usize,
    /// AdamW's learning rate; it falls to a quarter for the last third of the steps.
    pub learning_rate: f64,
    pub weight_decay: f64,
    /// Weight of a wall pixel in the loss (paper and other ink weigh 1).
    pub wall_weight: f32,
    /// Share of crops centred on a wall pixel (the rest anywhere).
    pub on_wall: f64,
    pub working: Working,
}

impl Default for NetParams {
    fn default() -> Self {
        NetParams {
            seed: 1,
            steps: 600,
            batch: 6,
            crop: 160,
            learning_rate: 2e-3,
            weight_decay: 1e-4,
            wall_weight: 1.5,
            on_wall: 0.7,
            working: Working::default(),
        }
    }
}

/// A training drawing as the network reads it.
struct Prepared {
    w: usize,
    h: usize,
    x: Vec<f32>,
    truth: Vec<u8>,
}

fn prepare(s: &Sheet, working: &Working) -> Prepared {
    let (x, w, h) = input(&s.grey, working);
    let truth = if (w as u32, h as u32) == s.truth.dimensions() {
        s.truth.as_raw().clone()
    } else {
        image::imageops::resize(
            &s.truth,
            w as u32,
            h as u32,
            image::imageops::FilterType::Nearest,
        )
        .into_raw()
    };
    Prepared { w, h, x, truth }
}

/// One crop of `p` into `x`, `y` and `weight` (each `crop`²), drawn by `rng`.
fn crop_into(
    p: &Prepared,
    np: &NetParams,
    rng: &mut ChaCha8Rng,
    out: (&mut Vec<f32>, &mut Vec<f32>, &mut Vec<f32>),
) {
    let s = np.crop;
    let (cw, ch) = (s.min(p.w), s.min(p.h));
    let centre = if rng.random_bool(np.on_wall) {
        (0..50).find_map(|_| {
            let i = rng.random_range(0..p.truth.len());
            (p.truth[i] == WALL).then_some((i % p.w, i / p.w))
        })
    } else {
        None
    };
    let (x0, y0) = match centre {
        Some((cx, cy)) => (
            cx.saturating_sub(cw / 2).min(p.w - cw),
            cy.saturating_sub(ch / 2).min(p.h - ch),
        ),
        None => (
            rng.random_range(0..=p.w - cw),
            rng.random_range(0..=p.h - ch),
        ),
    };
    let (flip_x, flip_y, transpose) = (
        rng.random_bool(0.5),
        rng.random_bool(0.5),
        rng.random_bool(0.5),
    );
    let gain: f32 = rng.random_range(0.7..1.2);
    let (xs, ys, ws) = out;
    for j in 0..s {
        for i in 0..s {
            let (mut a, mut b) = if transpose { (j, i) } else { (i, j) };
            if flip_x {
                a = s - 1 - a;
            }
            if flip_y {
                b = s - 1 - b;
            }
            if a >= cw || b >= ch {
                xs.push(0.0);
                ys.push(0.0);
                ws.push(0.0);
                continue;
            }
            let k = (y0 + b) * p.w + x0 + a;
            xs.push((p.x[k] * gain).min(1.0));
            let t = p.truth[k];
            ys.push(f32::from(u8::from(t == WALL)));
            ws.push(match t {
                IGNORE => 0.0,
                WALL => np.wall_weight,
                _ => 1.0,
            });
        }
    }
}

/// Overwrites every weight with a seeded He-uniform draw and every bias with 0, in name order.
fn seeded_init(vm: &VarMap, seed: u64) -> candle_core::Result<()> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6e65_7431);
    let data = vm.data().lock().expect("the var map is not shared");
    let mut names: Vec<&String> = data.keys().collect();
    names.sort();
    for name in names {
        let var = &data[name];
        let dims = var.dims().to_vec();
        let n = var.elem_count();
        let values: Vec<f32> = if name.ends_with("bias") {
            vec![0.0; n]
        } else {
            let fan_in: usize = dims[1..].iter().product();
            let bound = (6.0 / fan_in as f64).sqrt();
            (0..n)
                .map(|_| rng.random_range(-bound..bound) as f32)
                .collect()
        };
        var.set(&Tensor::from_vec(values, dims, &Device::Cpu)?)?;
    }
    Ok(())
}

/// Trains a network on `painted` and `synthetic` drawings (each step draws its crops from one
/// of the two pools, with even odds, so the few painted drawings weigh as much as the many
/// synthetic ones). `progress` hears the step and the running loss every 50 steps.
pub fn train_net(
    painted: &[Sheet],
    synthetic: &[Sheet],
    np: &NetParams,
    provenance: &str,
    progress: &mut dyn FnMut(usize, f32),
) -> candle_core::Result<(WallNet, Vec<u8>)> {
    let pools: Vec<Vec<Prepared>> = [painted, synthetic]
        .iter()
        .map(|sheets| sheets.iter().map(|s| prepare(s, &np.working)).collect())
        .filter(|p: &Vec<Prepared>| !p.is_empty())
        .collect();
    if pools.is_empty() {
        candle_core::bail!("no training drawings");
    }
    let dev = Device::Cpu;
    let vm = VarMap::new();
    let vb = VarBuilder::from_varmap(&vm, DType::F32, &dev);
    let net = Unet::new(&vb)?;
    seeded_init(&vm, np.seed)?;
    let mut opt = AdamW::new(
        vm.all_vars(),
        ParamsAdamW {
            lr: np.learning_rate,
            weight_decay: np.weight_decay,
            ..Default::default()
        },
    )?;
    let mut rng = ChaCha8Rng::seed_from_u64(np.seed);
    let (b, s) = (np.batch, np.crop);
    let mut running = 0.0f32;
    for step in 0..np.steps {
        let pool = &pools[rng.random_range(0..pools.len())];
        let (mut xs, mut ys, mut ws) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..b {
            let p = &pool[rng.random_range(0..pool.len())];
            crop_into(p, np, &mut rng, (&mut xs, &mut ys, &mut ws));
        }
        let x = Tensor::from_vec(xs, (b, 1, s, s), &dev)?;
        let y = Tensor::from_vec(ys, (b, 1, s, s), &dev)?;
        let weight = Tensor::from_vec(ws, (b, 1, s, s), &dev)?;
        let z = net.forward(&x)?;
        // Logistic loss, stable: softplus(z) − y z = max(z, 0) + ln(1 + e^−|z|) − y z.
        let softplus = (z.relu()? + (z.abs()?.neg()?.exp()? + 1.0)?.log()?)?;
        let per_pixel = ((softplus - (&y * &z)?)? * &weight)?;
        let total = weight.sum_all()?.to_scalar::<f32>()?;
        let loss = (per_pixel.sum_all()? / f64::from(total.max(1.0)))?;
        if step == np.steps * 2 / 3 {
            opt.set_learning_rate(np.learning_rate / 4.0);
        }
        opt.backward_step(&loss)?;
        let l = loss.to_scalar::<f32>()?;
        running = if step == 0 {
            l
        } else {
            0.98 * running + 0.02 * l
        };
        if step % 50 == 0 || step + 1 == np.steps {
            progress(step, running);
        }
    }
    let bytes = to_bytes(&vm, &np.working, provenance)?;
    let net = WallNet::from_bytes(&bytes).map_err(|e| candle_core::Error::Msg(e.to_string()))?;
    Ok((net, bytes))
}

/// The network file: the weights in name order, the format, the working side and the
/// provenance as metadata.
fn to_bytes(vm: &VarMap, working: &Working, provenance: &str) -> candle_core::Result<Vec<u8>> {
    let data = vm.data().lock().expect("the var map is not shared");
    let mut names: Vec<&String> = data.keys().collect();
    names.sort();
    let tensors: Vec<(String, Tensor)> = names
        .into_iter()
        .map(|n| (n.clone(), data[n].as_tensor().clone()))
        .collect();
    let raw: Vec<(String, Vec<usize>, Vec<u8>)> = tensors
        .iter()
        .map(|(n, t)| {
            let v = t.flatten_all()?.to_vec1::<f32>()?;
            let bytes = v.iter().flat_map(|f| f.to_le_bytes()).collect();
            Ok((n.clone(), t.dims().to_vec(), bytes))
        })
        .collect::<candle_core::Result<_>>()?;
    let views: Vec<(String, safetensors::tensor::TensorView)> = raw
        .iter()
        .map(|(n, shape, bytes)| {
            let view =
                safetensors::tensor::TensorView::new(safetensors::Dtype::F32, shape.clone(), bytes)
                    .map_err(|e| candle_core::Error::Msg(e.to_string()))?;
            Ok((n.clone(), view))
        })
        .collect::<candle_core::Result<_>>()?;
    let header = NetHeader {
        format: NET_FORMAT,
        max_side: working.max_side,
        provenance: provenance.to_string(),
    };
    let header = serde_json::to_string(&header).expect("a header always serialises");
    let meta = std::collections::HashMap::from([(HEADER_KEY.to_string(), header)]);
    safetensors::serialize(views, Some(meta)).map_err(|e| candle_core::Error::Msg(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ink::train::fixtures::sheet;

    fn tiny(seed: u64) -> NetParams {
        NetParams {
            seed,
            steps: 3,
            batch: 2,
            crop: 32,
            ..NetParams::default()
        }
    }

    #[test]
    fn training_is_deterministic_from_its_seed() {
        let painted = [sheet(1)];
        let synthetic = [sheet(2)];
        let run = |seed| {
            train_net(&painted, &synthetic, &tiny(seed), "toy", &mut |_, _| {})
                .unwrap()
                .1
        };
        let a = run(1);
        assert_eq!(a, run(1));
        assert_ne!(a, run(2));
        let net = WallNet::from_bytes(&a).unwrap();
        assert_eq!(net.provenance, "toy");
        // Every pixel of the toy sheet gets a probability.
        let p = net.wall_probability(&painted[0].grey, 90, 70);
        assert_eq!(p.len(), 90 * 70);
        assert!(p.iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn training_needs_drawings() {
        let e = train_net(&[], &[], &tiny(1), "none", &mut |_, _| {}).unwrap_err();
        assert!(e.to_string().contains("no training drawings"), "{e}");
    }
}
