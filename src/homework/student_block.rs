//! The block of a student's own uniforms (binding 1), laid out as the translated WGSL lays it
//! out, and filled with the values their page gave those uniforms by name (`page`): a uniform
//! their page never set stays 0, as WebGL leaves it.

use std::collections::BTreeMap;

use super::interface::STUDENT_BLOCK_BINDING;

/// How a member's numbers are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Number {
    Float,
    Int,
    Uint,
}

/// One member of the block: `groups` runs of `components` 4-byte numbers, `stride` bytes apart
/// (a scalar or vector is one run; a matrix one per column; an array one per element).
#[derive(Clone, Debug, PartialEq, Eq)]
struct Member {
    name: String,
    offset_bytes: u32,
    number: Number,
    components: u32,
    groups: u32,
    stride_bytes: u32,
}

/// The student's block of one stage pair.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StudentBlock {
    pub size_bytes: u64,
    members: Vec<Member>,
}

fn number(scalar: naga::Scalar) -> Option<Number> {
    match scalar.kind {
        naga::ScalarKind::Float if scalar.width == 4 => Some(Number::Float),
        naga::ScalarKind::Sint if scalar.width == 4 => Some(Number::Int),
        naga::ScalarKind::Uint if scalar.width == 4 => Some(Number::Uint),
        _ => None,
    }
}

fn rows(size: naga::VectorSize) -> u32 {
    size as u32
}

/// (number, components, groups, stride) of a member's type; None for what a page cannot set.
fn shape(module: &naga::Module, ty: naga::Handle<naga::Type>) -> Option<(Number, u32, u32, u32)> {
    match &module.types[ty].inner {
        naga::TypeInner::Scalar(s) => Some((number(*s)?, 1, 1, 4)),
        naga::TypeInner::Vector { size, scalar } => Some((number(*scalar)?, rows(*size), 1, 16)),
        naga::TypeInner::Matrix { columns, rows: r, scalar } => {
            let stride = if rows(*r) == 2 { 8 } else { 16 };
            Some((number(*scalar)?, rows(*r), rows(*columns), stride))
        }
        naga::TypeInner::Array { base, size: naga::ArraySize::Constant(len), stride } => {
            let (n, components, groups, _) = shape(module, *base)?;
            (groups == 1).then_some((n, components, len.get(), *stride))
        }
        _ => None,
    }
}

impl StudentBlock {
    /// The block a WGSL stage declares at binding 1 (empty where it declares none).
    pub fn of_wgsl(wgsl: &str) -> StudentBlock {
        let Ok(module) = naga::front::wgsl::parse_str(wgsl) else { return StudentBlock::default() };
        let mut layouter = naga::proc::Layouter::default();
        if layouter.update(module.to_ctx()).is_err() {
            return StudentBlock::default();
        }
        let Some((_, global)) = module.global_variables.iter().find(|(_, g)| {
            g.binding.as_ref().is_some_and(|b| b.group == 0 && b.binding == STUDENT_BLOCK_BINDING)
        }) else {
            return StudentBlock::default();
        };
        let members = match &module.types[global.ty].inner {
            naga::TypeInner::Struct { members, .. } => members
                .iter()
                .filter_map(|m| {
                    let (number, components, groups, stride_bytes) = shape(&module, m.ty)?;
                    Some(Member {
                        name: m.name.clone()?,
                        offset_bytes: m.offset,
                        number,
                        components,
                        groups,
                        stride_bytes,
                    })
                })
                .collect(),
            _ => Vec::new(),
        };
        StudentBlock { size_bytes: u64::from(layouter[global.ty].size), members }
    }

    /// The larger of two stages' blocks (both declare the same members, gathered from both).
    pub fn larger(self, other: StudentBlock) -> StudentBlock {
        if other.size_bytes > self.size_bytes { other } else { self }
    }

    /// The block's bytes with each member the page set, by name; the rest 0.
    pub fn bytes(&self, page: &BTreeMap<String, Vec<f64>>) -> Vec<u8> {
        let mut out = vec![0u8; self.size_bytes.max(16).next_multiple_of(16) as usize];
        for member in &self.members {
            let Some(values) = page.get(&member.name) else { continue };
            let mut values = values.iter();
            'groups: for group in 0..member.groups {
                for component in 0..member.components {
                    let Some(&v) = values.next() else { break 'groups };
                    let at = (member.offset_bytes + group * member.stride_bytes + 4 * component) as usize;
                    let word = match member.number {
                        Number::Float => (v as f32).to_le_bytes(),
                        Number::Int => (v as i32).to_le_bytes(),
                        Number::Uint => (v as u32).to_le_bytes(),
                    };
                    if let Some(slot) = out.get_mut(at..at + 4) {
                        slot.copy_from_slice(&word);
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pages_values_land_where_the_block_lays_them_out() {
        let wgsl = "struct Student { uFrustumSize: f32, uCount: i32, uDir: vec3<f32>, uM: mat3x3<f32>, uW: array<vec4<f32>, 2> }
@group(0) @binding(1) var<uniform> student: Student;
@fragment fn main() -> @location(0) vec4<f32> { return vec4<f32>(student.uFrustumSize); }";
        let block = StudentBlock::of_wgsl(wgsl);
        assert_eq!(block.size_bytes, 112);
        let page: BTreeMap<String, Vec<f64>> = [
            ("uFrustumSize".to_string(), vec![340.0]),
            ("uCount".to_string(), vec![3.0]),
            ("uDir".to_string(), vec![1.0, 2.0, 3.0]),
            ("uM".to_string(), (1..=9).map(f64::from).collect()),
            ("uW".to_string(), (1..=8).map(f64::from).collect()),
            ("uUnknown".to_string(), vec![9.0]),
        ]
        .into_iter()
        .collect();
        let bytes = block.bytes(&page);
        let f = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
        let i = |at: usize| i32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
        assert_eq!(f(0), 340.0);
        assert_eq!(i(4), 3);
        assert_eq!([f(16), f(20), f(24)], [1.0, 2.0, 3.0]);
        // mat3x3: columns 16 bytes apart.
        assert_eq!([f(32), f(36), f(40), f(48), f(64), f(72)], [1.0, 2.0, 3.0, 4.0, 7.0, 9.0]);
        assert_eq!([f(80), f(92), f(96), f(108)], [1.0, 4.0, 5.0, 8.0]);
        // Nothing set: zeros, as WebGL leaves an unset uniform.
        assert!(block.bytes(&BTreeMap::new()).iter().all(|b| *b == 0));
    }
}
