use daegen::prelude::*;
include!("/tmp/oss_unrolled.rs");
fn main() -> Result<(), daegen::Error> {
    for compact in [false, true, false, true] {
        let opts = Options::new().method(Method::Taylor).rtol(1e-15).atol(1e-15).taylor_compact(compact);
        let start = std::time::Instant::now();
        let sol = OuterSolarSystem::default().simulate(0.0, 200000.0, &opts)?;
        println!("compact {compact}: {} steps, {:?}", sol.stats().steps, start.elapsed());
    }
    Ok(())
}
