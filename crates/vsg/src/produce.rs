//! The production process (§7.1.3): starting from `Axiom`, apply one rule to each non-terminal
//! shape (chosen among those whose condition holds, by probability, from a seeded stream)
//! until only terminals remain, keeping every non-terminal in the semantic tree.

use std::collections::HashMap;

use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use crate::ast::{AppearanceValue, Expr, Length, OpKind, Span};
use crate::compile::{Compiled, CompiledRule, Geometry, Succ};
use crate::csg::{self, MeshBoolean};
use crate::diag::{Diagnostic, num};
use crate::expr::{Scope, ShapeAttrs};
use crate::partition::{self, Len};
use crate::shape::{self, Axis, Primitive, ShapeError, Tessellation};
use crate::tree::{Appearance, Model, Node, NodeId, NodeState, TextureFrame, UniqueShape};

/// Bounds on production, so a runaway grammar stops with an error instead of eating memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Deepest allowed node (the root is depth 0).
    pub max_depth: u32,
    /// Most nodes (terminal and not) a production may create.
    pub max_shapes: usize,
    /// How finely curved primitives are meshed before a Boolean (§7.1.2 unique shapes are
    /// meshes, fixed at production).
    pub tessellation: Tessellation,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_depth: 100,
            max_shapes: 5_000_000,
            tessellation: Tessellation::default(),
        }
    }
}

struct Producer<'c, 'p> {
    program: &'c Compiled<'p>,
    limits: Limits,
    rng: ChaCha8Rng,
    model: Model,
    /// Set on nodes below a `void()`: their terminals are void.
    void: Vec<bool>,
    appearance_ids: HashMap<Vec<u64>, u32>,
}

/// Runs the production of a compiled program.
pub fn produce(program: &Compiled, limits: Limits, rng: ChaCha8Rng) -> Result<Model, Diagnostic> {
    let mut p = Producer {
        program,
        limits,
        rng,
        model: Model {
            symbols: program.symbols.clone(),
            ..Model::default()
        },
        void: vec![false],
        appearance_ids: HashMap::new(),
    };
    p.intern_appearance(Appearance::default());
    p.model.nodes.push(Node {
        symbol: program.axiom,
        rule_line: 0,
        shape: None,
        local: Isometry3::identity(),
        world: Isometry3::identity(),
        appearance: 0,
        state: NodeState::NonTerminal,
        parent: None,
        first_child: 0,
        child_count: 0,
        depth: 0,
        index: 0,
    });
    let mut stack: Vec<NodeId> = vec![0];
    while let Some(id) = stack.pop() {
        let children = p.expand(id)?;
        for c in children.rev() {
            if p.model.nodes[c as usize].state == NodeState::NonTerminal {
                stack.push(c);
            }
        }
    }
    Ok(p.model)
}

/// A shape a rule hands to one successor: where it sits in the predecessor's frame.
struct Output {
    shape: Option<Primitive>,
    /// A unique shape made by a Boolean (then `shape` is `None`).
    unique: Option<UniqueShape>,
    local: Isometry3<f64>,
    successor: usize,
}

impl Producer<'_, '_> {
    fn attrs(&self, id: NodeId) -> ShapeAttrs {
        let n = &self.model.nodes[id as usize];
        let siblings = n
            .parent
            .map_or(1, |p| self.model.nodes[p as usize].child_count);
        let t = n.world.translation.vector;
        let solid = self.model.solid(id);
        ShapeAttrs {
            size: solid.map_or([0.0; 3], |s| s.size()),
            position: [t.x, t.y, t.z],
            volume: solid.map_or(0.0, |s| s.volume()),
            depth: n.depth,
            index: n.index,
            siblings,
        }
    }

    fn choose_rule(&mut self, id: NodeId, attrs: &ShapeAttrs) -> Result<usize, Diagnostic> {
        let program = self.program;
        let symbol = self.model.nodes[id as usize].symbol as usize;
        let candidates = &program.rules_by_symbol[symbol];
        if candidates.len() == 1 && program.rules[candidates[0]].ast.condition.is_none() {
            return Ok(candidates[0]);
        }
        let mut applicable = Vec::with_capacity(candidates.len());
        for &r in candidates {
            let rule = &program.rules[r];
            let mut scope = Scope {
                vars: &program.vars,
                shape: Some(attrs),
                rng: &mut self.rng,
            };
            let holds = match &rule.ast.condition {
                Some(c) => scope.truth(c)?,
                None => true,
            };
            if holds {
                let weight = match &rule.ast.probability {
                    Some(p) => {
                        let w = scope.eval(p)?;
                        if !(0.0..=1.0).contains(&w) {
                            return Err(Diagnostic::new(
                                format!("probability {} is outside 0..1", num(w)),
                                p.span(),
                                "probability",
                            ));
                        }
                        w
                    }
                    None => 1.0,
                };
                applicable.push((r, weight));
            }
        }
        let name = &program.symbols[symbol];
        let first = &program.rules[candidates[0]];
        let total: f64 = applicable.iter().map(|a| a.1).sum();
        if applicable.is_empty() || total <= 0.0 {
            return Err(Diagnostic::new(
                format!(
                    "no rule for '{name}' applies to this shape (size {:.4} x {:.4} x {:.4}, depth {}, index {}): every condition is false or every probability 0",
                    attrs.size[0], attrs.size[1], attrs.size[2], attrs.depth, attrs.index
                ),
                first.ast.span,
                "rules for this symbol",
            ));
        }
        // The probabilities of the applicable rules are normalised to sum to one.
        let chosen = if applicable.len() == 1 {
            applicable[0].0
        } else {
            let mut x = self.rng.random_range(0.0..total);
            let mut pick = applicable[applicable.len() - 1].0;
            for &(r, w) in &applicable {
                if x < w {
                    pick = r;
                    break;
                }
                x -= w;
            }
            pick
        };
        Ok(chosen)
    }

    fn expand(&mut self, id: NodeId) -> Result<std::ops::Range<NodeId>, Diagnostic> {
        let needs_attrs = {
            let symbol = self.model.nodes[id as usize].symbol as usize;
            self.program.rules_by_symbol[symbol].iter().any(|&r| {
                !self.program.rules[r].ast.ops.is_empty()
                    || self.program.rules[r].ast.condition.is_some()
            })
        };
        let attrs = if needs_attrs {
            self.attrs(id)
        } else {
            ShapeAttrs::default()
        };
        let program = self.program;
        let rule = &program.rules[self.choose_rule(id, &attrs)?];
        let (outputs, appearance, void) = self.apply(id, rule, &attrs)?;
        let node_appearance = self.model.nodes[id as usize].appearance;
        let appearance = match appearance {
            Some(a) => self.intern_appearance(a),
            None => node_appearance,
        };
        let void = void || self.void[id as usize];
        // `A :: ... {j3d.terminal}` with no new geometry ends A itself.
        if let [only] = outputs.as_slice()
            && rule.successors[only.successor] == Succ::Terminal
            && rule.geometry == Geometry::Keep
        {
            let n = &mut self.model.nodes[id as usize];
            if only.local != Isometry3::identity() {
                let world = n.world * only.local;
                let name = &self.model.symbols[n.symbol as usize];
                check_placement(&only.local, name, rule.ast.span)?;
                check_placement(&world, name, rule.ast.span)?;
                n.local *= only.local;
                n.world = world;
            }
            n.appearance = appearance;
            n.state = if void {
                NodeState::VoidTerminal
            } else {
                NodeState::Terminal
            };
            return Ok(0..0);
        }
        let first = self.model.nodes.len() as NodeId;
        let count = outputs.len() as u32;
        let parent = self.model.nodes[id as usize].clone();
        if parent.depth + 1 > self.limits.max_depth {
            return Err(Diagnostic::new(
                format!(
                    "production went deeper than {} levels at '{}': the grammar seems to recurse without end (raise the limit with --max-depth if it is meant)",
                    self.limits.max_depth, self.model.symbols[parent.symbol as usize]
                ),
                rule.ast.span,
                "this rule keeps producing",
            ));
        }
        if self.model.nodes.len() + outputs.len() > self.limits.max_shapes {
            return Err(Diagnostic::new(
                format!(
                    "production exceeded {} shapes (raise the limit with --max-shapes if it is meant)",
                    self.limits.max_shapes
                ),
                rule.ast.span,
                "creating shapes here",
            ));
        }
        for out in &outputs {
            let symbol = match rule.successors[out.successor] {
                Succ::Symbol(s) => s,
                Succ::Terminal => parent.symbol,
            };
            let name = &self.model.symbols[symbol as usize];
            // The local placement first: an infinite one turns into NaN in the world.
            check_placement(&out.local, name, rule.ast.span)?;
            check_placement(&(parent.world * out.local), name, rule.ast.span)?;
        }
        for (index, out) in outputs.into_iter().enumerate() {
            let (symbol, state) = match rule.successors[out.successor] {
                Succ::Symbol(s) => (s, NodeState::NonTerminal),
                Succ::Terminal if void => (parent.symbol, NodeState::VoidTerminal),
                Succ::Terminal => (parent.symbol, NodeState::Terminal),
            };
            if let Some(u) = out.unique {
                self.model
                    .unique
                    .insert(self.model.nodes.len() as NodeId, u);
            }
            self.model.nodes.push(Node {
                symbol,
                rule_line: rule.line,
                shape: out.shape,
                local: out.local,
                world: parent.world * out.local,
                appearance,
                state,
                parent: Some(id),
                first_child: 0,
                child_count: 0,
                depth: parent.depth + 1,
                index: index as u32,
            });
            self.void.push(void);
        }
        let n = &mut self.model.nodes[id as usize];
        n.first_child = first;
        n.child_count = count;
        Ok(first..first + count)
    }

    /// Runs a rule's functions in order on node `id`.
    fn apply(
        &mut self,
        id: NodeId,
        rule: &CompiledRule,
        attrs: &ShapeAttrs,
    ) -> Result<(Vec<Output>, Option<Appearance>, bool), Diagnostic> {
        let vars = &self.program.vars;
        let shape = self.model.nodes[id as usize].shape;
        let mut translation = Vector3::zeros();
        let mut rotation = UnitQuaternion::identity();
        let mut outputs = Vec::new();
        let mut appearance: Option<Appearance> = None;
        let mut void = false;
        let mut type_index = 0;
        for op in &rule.ast.ops {
            let mut scope = Scope {
                vars,
                shape: Some(attrs),
                rng: &mut self.rng,
            };
            match &op.kind {
                OpKind::Translate(e) => {
                    translation +=
                        Vector3::new(scope.eval(&e[0])?, scope.eval(&e[1])?, scope.eval(&e[2])?);
                }
                OpKind::Rotate(e) => {
                    let r = Rotation3::from_euler_angles(
                        scope.eval(&e[0])?,
                        scope.eval(&e[1])?,
                        scope.eval(&e[2])?,
                    );
                    rotation = UnitQuaternion::from_rotation_matrix(&r) * rotation;
                }
                OpKind::Instantiate { params, .. } => {
                    let kind = rule.types[type_index];
                    let values = params
                        .iter()
                        .map(|e| scope.eval(e))
                        .collect::<Result<Vec<_>, _>>()?;
                    let primitive = Primitive::new(kind, &values)
                        .map_err(|e| Diagnostic::new(e.to_string(), op.span, "invalid shape"))?;
                    // T() and R() before an I() place that shape: centre at T, orientation R.
                    outputs.push(Output {
                        unique: None,
                        shape: Some(primitive),
                        local: Isometry3::from_parts(Translation3::from(translation), rotation),
                        successor: type_index,
                    });
                    type_index += 1;
                    translation = Vector3::zeros();
                    rotation = UnitQuaternion::identity();
                }
                OpKind::Split { lengths, .. } | OpKind::Repeat { lengths, .. } => {
                    let Geometry::Divide { axis, .. } = rule.geometry else {
                        unreachable!("compile() marks rules with a split as Divide")
                    };
                    let Some(prim) = shape else {
                        return Err(Diagnostic::new(
                            format!(
                                "'{}' has no shape to divide; instantiate one with I() first",
                                self.model.symbols[self.model.nodes[id as usize].symbol as usize]
                            ),
                            op.span,
                            "nothing to split",
                        ));
                    };
                    let lens = lengths
                        .iter()
                        .map(|l| eval_len(&mut scope, l))
                        .collect::<Result<Vec<_>, _>>()?;
                    let shape_err =
                        |e: ShapeError| Diagnostic::new(e.to_string(), op.span, "this split");
                    let extent = prim.extent(axis).map_err(shape_err)?;
                    let part_err = |e: partition::PartitionError| {
                        Diagnostic::new(e.to_string(), op.span, "this split")
                    };
                    let (pieces_len, symbols): (Vec<f64>, Vec<usize>) = match &op.kind {
                        OpKind::Repeat { offset, .. } => {
                            let offset = match offset {
                                Some(e) => scope.eval(e)?,
                                None => 0.0,
                            };
                            let budget = self
                                .limits
                                .max_shapes
                                .saturating_sub(self.model.nodes.len());
                            partition::repeat(extent, &lens, offset, budget)
                                .map_err(part_err)?
                                .into_iter()
                                .unzip()
                        }
                        _ => (
                            partition::resolve_split(extent, &lens).map_err(part_err)?,
                            (0..lens.len()).collect(),
                        ),
                    };
                    let pieces = prim.split(axis, &pieces_len).map_err(shape_err)?;
                    let pending = Isometry3::from_parts(Translation3::from(translation), rotation);
                    outputs.extend(pieces.into_iter().zip(symbols).map(|(piece, successor)| {
                        Output {
                            unique: None,
                            shape: Some(piece.primitive),
                            local: pending * piece.transform,
                            successor,
                        }
                    }));
                }
                OpKind::Appearance(attrs_list) => {
                    let base = appearance.take().unwrap_or_else(|| {
                        self.model.appearances[self.model.nodes[id as usize].appearance as usize]
                            .clone()
                    });
                    let node = &self.model.nodes[id as usize];
                    let frame = shape.and_then(|p| {
                        let size = [Axis::X, Axis::Y, Axis::Z].map(|a| p.extent(a).ok());
                        Some(TextureFrame {
                            world: node.world,
                            size: [size[0]?, size[1]?, size[2]?],
                        })
                    });
                    appearance = Some(set_appearance(
                        base, attrs_list, rule.line, frame, &mut scope,
                    )?);
                }
                OpKind::Void => void = true,
                OpKind::Combine(kind) => {
                    // The meshes are placed before the Boolean: refuse absurd places first.
                    for o in &outputs {
                        check_placement(&o.local, "an operand", op.span)?;
                    }
                    let unique = self
                        .combine(*kind, &outputs)
                        .map_err(|e| Diagnostic::new(e.to_string(), op.span, "this Boolean"))?;
                    outputs = vec![Output {
                        shape: None,
                        unique: Some(unique),
                        local: Isometry3::identity(),
                        successor: 0,
                    }];
                }
            }
        }
        if outputs.is_empty() {
            // No I, split or repeat: every successor gets the predecessor's shape, moved by any
            // T() and R() of the rule.
            let local = Isometry3::from_parts(Translation3::from(translation), rotation);
            outputs = (0..rule.successors.len())
                .map(|successor| Output {
                    unique: None,
                    shape,
                    local,
                    successor,
                })
                .collect();
        }
        Ok((outputs, appearance, void))
    }

    /// The unique shape of `op` over the instantiated `outputs`, in the predecessor's frame.
    fn combine(&self, op: csg::BoolOp, outputs: &[Output]) -> Result<UniqueShape, csg::CsgError> {
        let meshes: Vec<_> = outputs
            .iter()
            .filter_map(|o| {
                let mut m = o.shape?.mesh(&self.limits.tessellation);
                for p in &mut m.positions {
                    let w = o.local * nalgebra::Point3::from(*p);
                    *p = [w.x, w.y, w.z];
                }
                Some(m)
            })
            .collect();
        let mesh = csg::Manifold.combine(op, &meshes)?;
        let volume = mesh.signed_volume();
        Ok(UniqueShape { op, mesh, volume })
    }

    fn intern_appearance(&mut self, a: Appearance) -> u32 {
        let mut key: Vec<u64> = a
            .color
            .iter()
            .chain(&a.diffuse)
            .chain(&a.specular)
            .chain(&a.emissive)
            .chain([a.transparency, a.ambient, a.shine].iter())
            .map(|v| v.to_bits())
            .collect();
        key.push(a.density.map_or(u64::MAX, f64::to_bits));
        key.push(u64::from(a.texture_line));
        if let Some(f) = &a.texture_frame {
            let t = f.world.translation.vector;
            let q = f.world.rotation.coords;
            key.extend(
                [t.x, t.y, t.z, q.x, q.y, q.z, q.w]
                    .iter()
                    .chain(&f.size)
                    .map(|v| v.to_bits()),
            );
        }
        if let Some(t) = &a.texture {
            key.extend(t.bytes().map(u64::from));
        }
        let next = self.model.appearances.len() as u32;
        let id = *self.appearance_ids.entry(key).or_insert(next);
        if id == next {
            self.model.appearances.push(a);
        }
        id
    }
}

/// Refuses a placement of the shape `what` that is not finite or lies farther than
/// [`shape::MAX_COORDINATE`] from the origin along an axis (see there why).
fn check_placement(at: &Isometry3<f64>, what: &str, span: Span) -> Result<(), Diagnostic> {
    let t = at.translation.vector;
    let finite_rotation = at.rotation.coords.iter().all(|c| c.is_finite());
    if t.iter().all(|&c| shape::within_bounds(c)) && finite_rotation {
        return Ok(());
    }
    Err(Diagnostic::new(
        format!(
            "'{what}' would be placed at ({}, {}, {}), more than {:e} m from the origin along an axis (shapes are stored as 32-bit floats); check the T() and split values that lead here",
            num(t.x),
            num(t.y),
            num(t.z),
            shape::MAX_COORDINATE
        ),
        span,
        "places a shape out of bounds",
    ))
}

fn eval_len(scope: &mut Scope, l: &Length) -> Result<Len, Diagnostic> {
    let v = scope.eval(&l.expr)?;
    Ok(if l.relative {
        Len::Relative(v)
    } else {
        Len::Absolute(v)
    })
}

const ATTRIBUTES: &str =
    "color, transparency, ambient, diffuse, specular, emissive, shine, texture, photo, density";

fn set_appearance(
    mut a: Appearance,
    list: &[(crate::ast::StrLit, AppearanceValue)],
    line: u32,
    frame: Option<TextureFrame>,
    scope: &mut Scope,
) -> Result<Appearance, Diagnostic> {
    for (name, value) in list {
        let span = name.span;
        match name.value.as_str() {
            // A photo stretched over the current shape (a rectified façade over its wall).
            "photo" => match (value, frame) {
                (AppearanceValue::Text(s), Some(f)) => {
                    a.texture = Some(s.value.clone());
                    a.texture_line = line;
                    a.texture_frame = Some(f);
                }
                (AppearanceValue::Text(_), None) => {
                    return Err(Diagnostic::new(
                        "photo needs a shape to stretch over; instantiate one with I() first",
                        span,
                        "photo",
                    ));
                }
                _ => {
                    return Err(Diagnostic::new(
                        "photo takes one file name in quotes",
                        span,
                        "photo",
                    ));
                }
            },
            "texture" => match value {
                // "" takes the texture (or photo) off: a wall's back behind its photo.
                AppearanceValue::Text(s) if s.value.is_empty() => {
                    a.texture = None;
                    a.texture_frame = None;
                }
                AppearanceValue::Text(s) => {
                    a.texture = Some(s.value.clone());
                    a.texture_line = line;
                    a.texture_frame = None;
                }
                // Figure 7.6: one of the photographs, picked per shape by the seeded stream.
                AppearanceValue::Texts(v) => {
                    let pick = scope.rng.random_range(0..v.len());
                    a.texture = Some(v[pick].value.clone());
                    a.texture_line = line;
                    a.texture_frame = None;
                }
                _ => {
                    return Err(Diagnostic::new(
                        "texture takes a file name in quotes, or a list {\"a.png\", \"b.png\"} to pick from",
                        span,
                        "texture",
                    ));
                }
            },
            "density" => a.density = Some(density(value, scope, span)?),
            "color" => a.color = rgb(value, scope, span)?,
            "diffuse" => a.diffuse = rgb(value, scope, span)?,
            "specular" => a.specular = rgb(value, scope, span)?,
            "emissive" => a.emissive = rgb(value, scope, span)?,
            "transparency" => a.transparency = unit(value, scope, span)?,
            "ambient" => a.ambient = unit(value, scope, span)?,
            "shine" => a.shine = unit(value, scope, span)?,
            other => {
                return Err(Diagnostic::new(
                    format!(
                        "unknown appearance attribute \"{other}\"; attributes are {ATTRIBUTES}"
                    ),
                    span,
                    "unknown attribute",
                ));
            }
        }
    }
    Ok(a)
}

fn component(e: &Expr, scope: &mut Scope) -> Result<f64, Diagnostic> {
    let v = scope.eval(e)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(Diagnostic::new(
            format!("appearance value {} is outside 0..1", num(v)),
            e.span(),
            "outside 0..1",
        ))
    }
}

fn unit(value: &AppearanceValue, scope: &mut Scope, span: Span) -> Result<f64, Diagnostic> {
    match value {
        AppearanceValue::Scalar(e) => component(e, scope),
        AppearanceValue::List(v) if v.len() == 1 => component(&v[0], scope),
        _ => Err(Diagnostic::new(
            "this attribute takes one number in 0..1",
            span,
            "one number",
        )),
    }
}

/// A density in kg/m³: one positive number (an extension for masses in STATS.json).
fn density(value: &AppearanceValue, scope: &mut Scope, span: Span) -> Result<f64, Diagnostic> {
    let e = match value {
        AppearanceValue::Scalar(e) => e,
        AppearanceValue::List(v) if v.len() == 1 => &v[0],
        _ => {
            return Err(Diagnostic::new(
                "density takes one number, in kg/m³",
                span,
                "one number",
            ));
        }
    };
    let v = scope.eval(e)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Diagnostic::new(
            format!("density {} must be a positive number of kg/m³", num(v)),
            e.span(),
            "not a density",
        ))
    }
}

fn rgb(value: &AppearanceValue, scope: &mut Scope, span: Span) -> Result<[f64; 3], Diagnostic> {
    match value {
        AppearanceValue::List(v) if v.len() == 3 => Ok([
            component(&v[0], scope)?,
            component(&v[1], scope)?,
            component(&v[2], scope)?,
        ]),
        AppearanceValue::Scalar(e) => {
            let g = component(e, scope)?;
            Ok([g; 3])
        }
        _ => Err(Diagnostic::new(
            "this attribute takes {r, g, b} in 0..1, or one grey value",
            span,
            "{r, g, b}",
        )),
    }
}
