# crashtest's command in an image, for running sharded campaigns on a cluster
# (docs/SCALE.md, docs/scale/crashtest-job.yaml). It judges the built-in
# engines; the peer engines' Python packages are not in it.
#
#   docker build -t crashtest:latest .
#   docker run --rm -v "$PWD/reports:/crashtest/reports" crashtest:latest report
FROM rust:1.89-bookworm AS build
WORKDIR /src
COPY . .
RUN cargo build --release -p crashtest-cli

FROM debian:bookworm-slim
COPY --from=build /src/target/release/crashtest /usr/local/bin/crashtest
COPY --from=build /src/fixtures /crashtest/fixtures
WORKDIR /crashtest
ENTRYPOINT ["crashtest"]
