//! Which surface is shown at a point of an output, for input routing: the outputs' places,
//! the candidates under the point and one depth read of each.

use super::pick::{winner, Picker, Target};
use super::state::Root;

impl Root {
    /// The output named `name` (empty: the first): its name and its rectangle in the output
    /// space.
    pub fn output(&self, name: &str) -> Result<(String, [i32; 4]), String> {
        let places = &self.places;
        let place = if name.is_empty() { places.first() } else { places.iter().find(|(n, _)| n == name) };
        place.cloned().ok_or_else(|| {
            let names: Vec<&str> = places.iter().map(|(n, _)| n.as_str()).collect();
            format!("no output named {name:?}; outputs: {}", names.join(", "))
        })
    }

    /// The surface shown at point `p` (output space) that accepts input, if any.
    pub fn pick(&self, p: [f32; 2]) -> Result<Option<Target>, String> {
        // The frames stay marked as picked until the read completes, so that no client draws
        // into them; a composite may read them meanwhile.
        let (damage, cands) = self.scene.input_candidates(p);
        if cands.is_empty() {
            return Ok(None);
        }
        let mut picker = self.picker.lock().map_err(|_| "input routing is unavailable")?;
        let picker = picker.get_or_insert_with(Picker::new);
        let own = self.scene.pick_device();
        let readings = picker.read(&self.gpu, own.as_deref(), damage, &cands);
        self.scene.end_input_read(&cands);
        let (readings, device_us) = readings.ok_or("reading the surfaces' texels under the point failed")?;
        Ok(winner(&cands, &readings).map(|i| Target {
            surface: cands[i].id,
            client: cands[i].client,
            local: cands[i].local,
            device_us,
        }))
    }

    /// Texels input routing has read so far: on the pick device, and on the compositor's.
    pub fn pick_reads(&self) -> [u64; 2] {
        self.picker.lock().ok().and_then(|p| p.as_ref().map(|p| p.reads)).unwrap_or([0; 2])
    }
}
