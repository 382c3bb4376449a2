//! Writes the generated sample race to stdout (`scripts/gen-fleet-race.sh` puts it in
//! `assets/races/fleet.json`); the generator is `race::synth`.

fn main() {
    print!("{}", race::synth::fleet_race_json());
}
