//! The viewer's camera. Right-handed world, +Y up, wgpu clip space (depth 0..1).

use glam::{Mat4, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    Perspective {
        fov_deg: f32,
    },
    /// `height_world`: world units covered by the view's height.
    Orthographic {
        height_world: f32,
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub projection: Projection,
    pub position: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub near: f32,
    pub far: f32,
}

impl Camera {
    pub fn view_from_world(&self) -> Mat4 {
        let forward = (self.target - self.position).normalize_or(Vec3::NEG_Z);
        Mat4::look_to_rh(self.position, forward, super::light::safe_up(forward, self.up))
    }

    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        match self.projection {
            Projection::Perspective { fov_deg } => {
                Mat4::perspective_rh(fov_deg.to_radians(), aspect, self.near, self.far)
            }
            Projection::Orthographic { height_world } => {
                let h = height_world * 0.5;
                let w = h * aspect;
                Mat4::orthographic_rh(-w, w, -h, h, self.near, self.far)
            }
        }
    }

    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        self.clip_from_view(aspect) * self.view_from_world()
    }

    /// Orbit about the target: yaw about the up axis and pitch, both in radians.
    pub fn orbit(&mut self, yaw_rad: f32, pitch_rad: f32) {
        let offset = self.position - self.target;
        let radius = offset.length();
        if radius <= 0.0 || !radius.is_finite() {
            return;
        }
        let up = self.up.normalize_or(Vec3::Y);
        let yawed = glam::Quat::from_axis_angle(up, yaw_rad) * offset;
        let right = yawed.cross(up).normalize_or(Vec3::X);
        let pitched = glam::Quat::from_axis_angle(right, pitch_rad) * yawed;
        // Keep away from the poles, where look_at degenerates.
        let cos_to_up = pitched.normalize().dot(up);
        let candidate = if cos_to_up.abs() < 0.995 { pitched } else { yawed };
        self.position = self.target + candidate.normalize() * radius;
    }

    /// Move position and target together, in view-plane world units.
    pub fn pan(&mut self, right_world: f32, up_world: f32) {
        let forward = (self.target - self.position).normalize_or(Vec3::NEG_Z);
        let right = forward.cross(self.up).normalize_or(Vec3::X);
        let up = right.cross(forward);
        let delta = right * right_world + up * up_world;
        self.position += delta;
        self.target += delta;
    }

    /// Scale the distance to the target (factor < 1 moves closer); orthographic height scales too.
    pub fn zoom(&mut self, factor: f32) {
        if !(factor.is_finite() && factor > 0.0) {
            return;
        }
        let offset = self.position - self.target;
        let new_len = (offset.length() * factor).clamp(self.near * 2.0, self.far * 0.9);
        self.position = self.target + offset.normalize_or(Vec3::Z) * new_len;
        if let Projection::Orthographic { height_world } = &mut self.projection {
            *height_world = (*height_world * factor).max(1e-3);
        }
    }
}
