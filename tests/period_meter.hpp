#pragma once
// The period of an oscillation from the times a sampled value crosses zero going down, each
// crossing placed within its step by linear interpolation.

namespace anyphys::test {

class PeriodMeter {
public:
    /// The value at time t, sampled every `dt` seconds.
    void add(double t, double dt, double value) {
        if (started_ && previous_ > 0.0 && value <= 0.0) {
            const double crossing = t - dt * value / (value - previous_);
            if (first_ < 0.0) first_ = crossing;
            last_ = crossing;
            ++crossings_;
        }
        previous_ = value;
        started_ = true;
    }
    int crossings() const { return crossings_; }
    /// The mean period between the first and the last crossing; 0 before two.
    double period() const { return crossings_ > 1 ? (last_ - first_) / (crossings_ - 1) : 0.0; }

private:
    double previous_ = 0.0, first_ = -1.0, last_ = -1.0;
    int crossings_ = 0;
    bool started_ = false;
};

}  // namespace anyphys::test
