//! The phones the host shows: their screens as Android reports them (pixels and density).

/// A phone the app targets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Device {
    /// Google Pixel 2 XL: 1440 × 2880 pixels, density 560 dpi (3.5 pixels per dp).
    #[default]
    #[value(name = "pixel2xl")]
    Pixel2Xl,
    /// OPPO A54: 720 × 1600 pixels, density 320 dpi (2 pixels per dp): 360 × 800 dp.
    #[value(name = "a54")]
    A54,
}

impl Device {
    /// The screen in portrait, physical pixels.
    pub fn pixels(self) -> [u32; 2] {
        match self {
            Device::Pixel2Xl => [1440, 2880],
            Device::A54 => [720, 1600],
        }
    }

    /// Physical pixels per dp (Android's density over its 160 dpi baseline).
    pub fn pixels_per_dp(self) -> f32 {
        match self {
            Device::Pixel2Xl => 3.5,
            Device::A54 => 2.0,
        }
    }

    /// The host's stand-in screen: half the phone's pixels per side (lavapipe and a laptop
    /// screen both prefer it), the same layout in dp.
    pub fn host_size(self) -> [u32; 2] {
        let [w, h] = self.pixels();
        [w / 2, h / 2]
    }

    /// Pixels per egui point for a screen of `size` pixels standing in for this phone: its
    /// layout in dp kept, whatever the pixels.
    pub fn pixels_per_point(self, size: [u32; 2]) -> f32 {
        let [w, _] = self.pixels();
        self.pixels_per_dp() * size[0] as f32 / w as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_a54_is_360_by_800_dp_at_any_host_size() {
        for size in [Device::A54.pixels(), Device::A54.host_size(), [180, 400]] {
            let ppp = Device::A54.pixels_per_point(size);
            assert_eq!([size[0] as f32 / ppp, size[1] as f32 / ppp], [360.0, 800.0]);
        }
        let p = Device::Pixel2Xl;
        let ppp = p.pixels_per_point(p.host_size());
        assert!((p.host_size()[0] as f32 / ppp - 1440.0 / 3.5).abs() < 1e-3);
    }
}
